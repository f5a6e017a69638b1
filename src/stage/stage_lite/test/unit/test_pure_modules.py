"""stage_lite's model and the node's pure helpers import no rospy: each is imported alone in a
fresh interpreter, which then must not have rospy (nor genpy, rosgraph) loaded."""
import os
import subprocess
import sys

import pytest

PACKAGE = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'src',
                       'stage_lite')
MODEL = sorted('stage_lite.model.' + name[:-3]
               for name in os.listdir(os.path.join(PACKAGE, 'model'))
               if name.endswith('.py') and name != '__init__.py')
# The node's pure helpers: the glue modules (stageros_node, step_loop, ...) import rospy.
HELPERS = ['stage_lite.node.' + name for name in (
    'map_msg', 'names', 'pacing', 'stageros_args', 'wire', 'world_picture', 'world_view')] \
    + ['stage_lite.testing.golden', 'stage_lite.testing.room']
CHECK = ('import importlib, sys; importlib.import_module(sys.argv[1]); '
         "print(sorted(m for m in ('rospy', 'genpy', 'rosgraph') if m in sys.modules))")


def test_every_model_module_is_listed():
    assert {'stage_lite.model.world', 'stage_lite.model.grid', 'stage_lite.model.worldfile'} \
        <= set(MODEL)


@pytest.mark.parametrize('module', MODEL + HELPERS)
def test_imports_no_rospy(module):
    out = subprocess.run([sys.executable, '-c', CHECK, module], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == '[]', '%s loads %s' % (module, out.strip())
