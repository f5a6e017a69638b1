"""Unit tests of course_common.rviz.config: the topics a .rviz file makes rviz subscribe to."""

import os

import pytest
from course_common.rviz.config import display_topics, fixed_frame

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.normpath(os.path.join(HERE, '..', '..', '..'))  # the workspace's src/


def _config(displays):
    lines = ['Visualization Manager:', '  Global Options:', '    Fixed Frame: world',
             '  Displays:']
    for display in displays:
        first = True
        for key, value in display.items():
            lines.append('    %s %s: %s' % ('-' if first else ' ', key, value))
            first = False
    return '\n'.join(lines) + '\n'


@pytest.mark.parametrize('displays, topics', [
    ([{'Class': 'rviz/Grid', 'Enabled': 'true'}], []),
    ([{'Class': 'rviz/TF', 'Enabled': 'true'}], ['/tf', '/tf_static']),
    ([{'Class': 'rviz/MarkerArray', 'Marker Topic': '/lesson_markers'}], ['/lesson_markers']),
    ([{'Class': 'rviz/Path', 'Topic': 'robot1/trail'}], ['/robot1/trail']),
    ([{'Class': 'rviz/MarkerArray', 'Enabled': 'false', 'Marker Topic': '/off'}], []),
    ([{'Class': 'rviz/MarkerArray', 'Marker Topic': '""'}], []),
    ([{'Class': 'rviz/TF'}, {'Class': 'rviz/MarkerArray', 'Marker Topic': '/a'},
      {'Class': 'rviz/MarkerArray', 'Marker Topic': '/a'}], ['/a', '/tf', '/tf_static']),
])
def test_display_topics(displays, topics):
    assert display_topics(_config(displays)) == topics


def test_groups_are_searched():
    text = ('Visualization Manager:\n  Displays:\n    - Class: rviz/Group\n      Displays:\n'
            '        - Class: rviz/MarkerArray\n          Marker Topic: /inner\n')
    assert display_topics(text) == ['/inner']


@pytest.mark.parametrize('text', ['', 'just text', '[1, 2]', 'Panels: []\n', ': : :\n  - ]',
                                  'Visualization Manager:\n  Displays:\n    - 3\n'])
def test_not_an_rviz_file(text):
    with pytest.raises(ValueError):
        display_topics(text)


STAGE_ROBOTS = range(4)


@pytest.mark.parametrize('path, topics, frame', [
    ('turtle_lite/turtle_lite/rviz/turtlesim.rviz', ['/lesson_markers', '/tf', '/tf_static'],
     'world'),
    ('multi_sync/rviz/multi_sync_turtlesim.rviz', ['/lesson_markers', '/tf', '/tf_static'],
     'world'),
    ('convoy/rviz/convoy.rviz', ['/convoy_gaps', '/lesson_markers', '/tf', '/tf_static'],
     'world'),
    # The Stage lesson: stageros's /map (~publish_map) and each robot's scan and ground truth.
    ('multi_sync/rviz/multi_sync.rviz',
     sorted(['/map', '/tf', '/tf_static']
            + ['/robot_%d/base_scan' % i for i in STAGE_ROBOTS]
            + ['/robot_%d/base_pose_ground_truth' % i for i in STAGE_ROBOTS]), 'map'),
])
def test_the_lessons_files(path, topics, frame):
    with open(os.path.join(SRC, path)) as f:
        text = f.read()
    assert display_topics(text) == topics
    assert fixed_frame(text) == frame
