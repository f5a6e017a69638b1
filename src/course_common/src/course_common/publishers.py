"""Publishers without a send queue, through rospy's public API; a greeting for each new
subscriber (OnNewSubscriber); a publisher's lost subscribers found and given the publisher
again (LostSubscribers)."""
import time
import warnings

import rosgraph
import rospy

from course_common.rospy_internals import connection_ids

#: The start of the SyntaxWarning rospy gives for a Publisher made without queue_size.
QUEUE_SIZE_WARNING = "The publisher should be created with an explicit keyword argument"


def unqueued_publisher(name, data_class, **kwargs):
    """A rospy Publisher without a send queue (rospy's documented ``queue_size=None``).

    publish() then writes to every subscriber's socket from the calling thread before it
    returns: no QueuedConnection, no sender thread per subscriber woken for each message.
    multi_sync uses it where a message must leave at once (GO, the first command) or before
    the process exits (the final stop); the simulator for its 62.5 Hz pose and colour topics,
    whose connections course_common.rospy_internals.write_frame() writes frames to.
    rospy's warning about the missing queue_size is silenced for this call only: here it is
    deliberate.
    """
    with warnings.catch_warnings():
        warnings.filterwarnings('ignore', message=QUEUE_SIZE_WARNING, category=SyntaxWarning)
        return rospy.Publisher(name, data_class, queue_size=None, **kwargs)


class OnNewSubscriber(rospy.SubscribeListener):
    """A Publisher's subscriber_listener that calls callback(send) as each subscriber connects.

    send is rospy's peer_publish for that connection: send(msg) reaches that subscriber alone,
    so a late joiner can be greeted without repeating the message to everyone (multi_sync:
    a robot's ready status to a monitor that starts late, the monitor's GO to a robot that
    subscribes after it).
    """

    def __init__(self, callback):
        super().__init__()
        self._callback = callback

    def peer_subscribe(self, topic_name, topic_publish, peer_publish):
        self._callback(peer_publish)


def still_unconnected(listed, connected, own_name, earlier):
    """(missing, lost): the subscribers the master lists for a topic (listed) that are not
    connected to this node's publisher (connected: their caller ids), and those of them that
    were missing at the check before too (earlier): one missed check is a subscriber still
    connecting, two are a lost connection. Pure."""
    missing = set(listed) - set(connected) - {own_name}
    return missing, missing & set(earlier)


class LostSubscribers:
    """Heals a publisher that a subscriber never connected to.

    The master tells a subscriber about a new publisher once (publisherUpdate), and rospy
    neither retries a lost call nor a connection that failed under load: the subscriber then
    never hears the publisher. team20 saw it: turtlesim never connected to one robot's
    cmd_vel, and that robot never moved. check(), called regularly (at most every period_s
    does anything), compares the master's subscribers of the topic with the publisher's
    connections; a subscriber missing twice in a row gets the publisher registered again,
    which makes the master send every subscriber the publisher list once more.
    """

    def __init__(self, pub, period_s=5.0, describe='%s'):
        """pub: a rospy Publisher; describe: the WARN's format, '%s' the text (e.g. a robot's
        'Robot 3: %s')."""
        self.pub = pub
        self.period_s = period_s
        self.describe = describe
        self._checked_at = time.monotonic()
        self._missing = set()

    def check(self):
        """Returns the subscribers it registered the publisher again for (empty if none)."""
        now = time.monotonic()
        if now - self._checked_at < self.period_s:
            return set()
        self._checked_at = now
        name = rospy.get_name()
        topic = self.pub.resolved_name
        try:
            master = rosgraph.Master(name)
            _, subscribers, _ = master.getSystemState()
            listed = next((nodes for t, nodes in subscribers if t == topic), [])
            self._missing, lost = still_unconnected(listed, connection_ids(self.pub), name,
                                                    self._missing)
            if lost:
                master.registerPublisher(topic, self.pub.type, rospy.get_node_uri())
                rospy.logwarn(self.describe % ('%s subscribe to %s but never connected: '
                                               'registered it again'
                                               % (', '.join(sorted(lost)), topic)))
        except (OSError, rosgraph.MasterError) as err:
            rospy.logdebug('publisher check of %s: %s', topic, err)
            return set()
        return lost
