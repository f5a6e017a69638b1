#!/usr/bin/env python3
"""stageros refuses bad command lines, world files and parameters: one FATAL line, exit 1."""

import rostest
from stage_support import StageTestCase, run_stageros, world


class StagerosBadInputTest(StageTestCase):
    NODE_NAME = 'stageros_bad_input_test'

    def _fails(self, args, *words, run=0):
        # A node name of its own: private parameters stay on the master after a run.
        name = '__name:=stageros_%s_%d' % (self.id().rsplit('.', 1)[-1], run)
        code, out = run_stageros(*args, name)
        self.assertEqual(code, 1, out)
        self.assertNotIn('Traceback', out)
        fatal = [line for line in out.splitlines() if 'FATAL' in line]
        self.assertEqual(len(fatal), 1, out)
        for word in words:
            self.assertIn(word, fatal[0])
        return fatal[0]

    def test_missing_world_file(self):
        path = world('node_no_such.world')
        self._fails(['-g', path], 'The world file %s does not exist.' % path)

    def test_syntax_error_names_file_and_line(self):
        self._fails(['-g', world('node_bad_syntax.world')], 'node_bad_syntax.world:4:')

    def test_missing_bitmap_names_the_world_and_the_bitmap(self):
        self._fails(['-g', world('node_bad_bitmap.world')], 'node_bad_bitmap.world',
                    'node_missing_map.pgm')

    def test_short_tuple_names_file_and_line(self):
        self._fails(['-g', world('node_bad_tuple.world')], 'node_bad_tuple.world:3:',
                    'pose needs 4 values, got 3')

    def test_a_controller_found_nowhere_names_file_and_line(self):
        self._fails(['-g', world('node_bad_ctrl.world')], 'node_bad_ctrl.world:7:',
                    'no controller "no_such_controller"')

    def test_no_world_file_prints_the_usage(self):
        self._fails(['-g'], 'Usage: stageros [-g] [-u] WORLD')

    def test_bad_parameter_names_it(self):
        self._fails(['-g', world('node_one_robot.world'), '_speedup:=0'], '~speedup', '0')
        self._fails(['-g', world('node_one_robot.world'), '_tf2_frames:=maybe'],
                    '~tf2_frames', 'maybe', run=1)


if __name__ == '__main__':
    rostest.rosrun('stage_lite', 'stageros_bad_input', StagerosBadInputTest)
