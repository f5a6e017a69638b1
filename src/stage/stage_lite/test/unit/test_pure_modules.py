"""stage_lite's pure modules import no rospy: each is imported alone in a fresh interpreter,
which then must not have rospy (nor genpy, rosgraph) loaded.

Pure are whole folders, found on disk: every module of model/, controllers/ (Stage's own
controllers), view/ (but the Tk window, gui, which logs through rospy) and testing/, and
every module of node/ but its ROS glue
(NODE_GLUE), so that a new module is checked without being listed anywhere.
"""
import os
import subprocess
import sys

import pytest

PACKAGE = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'src',
                       'stage_lite')
#: The node's modules that are rospy's by design: the node, its publishers, services,
#: stepping thread, rospy shortcuts and parameters.
NODE_GLUE = {'stageros_node', 'stage_publish', 'stage_services', 'step_loop', 'rospy_clock',
             'stageros_params', 'camera_publish'}
#: The view's one rospy module: the Tk window (it logs and shuts ROS down on File -> Exit).
VIEW_WINDOW = 'gui'
CHECK = ('import importlib, sys; importlib.import_module(sys.argv[1]); '
         "print(sorted(m for m in ('rospy', 'genpy', 'rosgraph') if m in sys.modules))")


def modules(folder, but=()):
    """The modules of stage_lite/<folder>/ (not its __init__), less those named in but."""
    return sorted('stage_lite.%s.%s' % (folder, name[:-3])
                  for name in os.listdir(os.path.join(PACKAGE, folder))
                  if name.endswith('.py') and name != '__init__.py' and name[:-3] not in but)


PURE = (modules('model') + modules('controllers') + modules('view', but={VIEW_WINDOW})
        + modules('node', but=NODE_GLUE) + modules('testing'))


def test_the_folders_are_found_and_the_exceptions_exist():
    assert {'stage_lite.model.world', 'stage_lite.model.grid', 'stage_lite.model.worldfile',
            'stage_lite.view.world_picture', 'stage_lite.view.camera',
            'stage_lite.node.wire', 'stage_lite.testing.golden',
            'stage_lite.controllers.wander', 'stage_lite.node.stage_program'} <= set(PURE)
    for name in NODE_GLUE:
        assert os.path.isfile(os.path.join(PACKAGE, 'node', name + '.py')), name
    assert os.path.isfile(os.path.join(PACKAGE, 'view', VIEW_WINDOW + '.py'))


@pytest.mark.parametrize('module', PURE)
def test_imports_no_rospy(module):
    out = subprocess.run([sys.executable, '-c', CHECK, module], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == '[]', '%s loads %s' % (module, out.strip())
