"""What an rviz configuration file subscribes to (no rospy): the topics its displays name.

rviz's .rviz files are YAML. Each display under ``Visualization Manager: Displays`` names its
input with a key ending in "Topic" ("Topic", "Marker Topic", ...); a TF display listens to
/tf and /tf_static. Disabled displays subscribe to nothing.
"""

import yaml

TF_TOPICS = ('/tf', '/tf_static')


def _displays(displays):
    """Every display, groups flattened (a rviz/Group holds its own Displays list)."""
    for display in displays or ():
        if not isinstance(display, dict):
            raise ValueError('display %r: expected a mapping' % (display,))
        yield display
        yield from _displays(display.get('Displays'))


def display_topics(text):
    """The sorted topics the enabled displays of a .rviz file's text subscribe to.

    Raises ValueError when the text is not an rviz configuration.
    """
    try:
        config = yaml.safe_load(text)
    except yaml.YAMLError as err:
        raise ValueError('not YAML: %s' % err) from err
    if not isinstance(config, dict) or not isinstance(config.get('Visualization Manager'), dict):
        raise ValueError('no "Visualization Manager" section: not an rviz configuration')
    topics = set()
    for display in _displays(config['Visualization Manager'].get('Displays')):
        if not display.get('Enabled', True):
            continue
        if display.get('Class') == 'rviz/TF':
            topics.update(TF_TOPICS)
        for key, value in display.items():
            if isinstance(key, str) and key.endswith('Topic') and isinstance(value, str) \
                    and value:
                topics.add(value if value.startswith('/') else '/' + value)
    return sorted(topics)


def fixed_frame(text):
    """The configuration's fixed frame (Global Options), or None when it names none."""
    config = yaml.safe_load(text)
    options = (config.get('Visualization Manager') or {}).get('Global Options') or {}
    return options.get('Fixed Frame')
