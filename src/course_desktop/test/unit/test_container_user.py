"""course_desktop.container_user: who runs the desktop in the image."""
import os
import subprocess
import sys

import pytest
from course_desktop.container_user import (
    IMAGE_GID,
    IMAGE_UID,
    can_write,
    cannot_write_message,
    choose_user,
    is_mount_point,
)


def test_the_folder_owner_runs_it():
    user = choose_user((0, 0), (1001, 121), mounted=True)
    assert (user.uid, user.gid, user.note) == (1001, 121, '')


def test_a_macos_folder_owner_with_a_taken_gid_is_still_taken():
    user = choose_user((0, 0), (501, 20), mounted=True)
    assert (user.uid, user.gid) == (501, 20)


def test_a_root_owned_folder_falls_back_to_the_images_student_and_says_why():
    user = choose_user((0, 0), (0, 0), mounted=True)
    assert (user.uid, user.gid) == (IMAGE_UID, IMAGE_GID)
    assert '--userns=keep-id' in user.note


def test_no_folder_mounted_warns_that_work_is_lost():
    user = choose_user((0, 0), (IMAGE_UID, IMAGE_GID), mounted=False)
    assert (user.uid, user.gid) == (IMAGE_UID, IMAGE_GID)
    assert 'lost when the container is removed' in user.note


@pytest.mark.parametrize('running', [(1000, 1000), (4242, 77)])
def test_started_as_a_user_it_stays_that_user(running):
    user = choose_user(running, (0, 0), mounted=True)
    assert (user.uid, user.gid) == running


def test_mount_points_from_mountinfo(tmp_path):
    mountinfo = tmp_path / 'mountinfo'
    mountinfo.write_text(
        '22 1 0:21 / / rw - overlay overlay rw\n'
        '35 22 8:1 /home/me/catkin_ws /home/student/catkin_ws rw - ext4 /dev/sda1 rw\n')
    assert is_mount_point('/home/student/catkin_ws', str(mountinfo))
    assert not is_mount_point('/home/student', str(mountinfo))
    assert not is_mount_point('/x', str(tmp_path / 'missing'))


def test_a_root_owned_folder_that_cannot_be_written_says_how_to_fix_it_on_the_host():
    message = cannot_write_message(IMAGE_UID, 0)
    assert 'mkdir catkin_ws' in message and 'sudo chown' in message
    assert '--userns=keep-id' in message


def test_a_folder_of_someone_else_says_to_give_write_permission():
    assert 'chmod u+rwx' in cannot_write_message(1001, 1001)


def test_can_write_tries_for_real(tmp_path):
    assert can_write(str(tmp_path))
    assert list(tmp_path.iterdir()) == []  # the probe file is gone
    assert not can_write(str(tmp_path / 'missing'))


def test_the_module_runs_its_main(tmp_path):
    # Without the image's folder the command says so and exits 1 (the image's `desktop`
    # runs this module with -m: a module that only defined main would exit 0 silently).
    done = subprocess.run([sys.executable, '-m', 'course_desktop.container_user'],
                          capture_output=True, text=True, timeout=60,
                          env=dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path)))
    if os.path.exists('/home/student/catkin_ws'):
        pytest.skip("this machine has the image's folder")
    assert done.returncode == 1
    assert '/home/student/catkin_ws cannot be read' in done.stderr
