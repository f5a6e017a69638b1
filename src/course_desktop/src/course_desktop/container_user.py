"""The image's `desktop` command: start as root, become the owner of the student's folder,
then run `./ws desktop` as that user (no service of the desktop runs as root).

`docker run -v "$PWD/catkin_ws:/home/student/catkin_ws" course-ws desktop`: the folder is the
student's on the host, so the desktop takes its owner's uid and gid and every file made in it
stays the student's. Where the folder shows as root's (Docker Desktop on Windows, rootless
Podman without --userns=keep-id), the image's own student (uid 1000) is used, if it can write
there; else one clear message and exit 1. Started as a non-root user already (`--user`,
Podman's keep-id), it runs as that user.
"""
import os
import pwd
import subprocess
import sys
import tempfile
from dataclasses import dataclass

HOME = '/home/student'
WORKSPACE = HOME + '/catkin_ws'
USER = 'student'
IMAGE_UID = IMAGE_GID = 1000  # the image's student (Dockerfile)


@dataclass(frozen=True)
class DesktopUser:
    uid: int
    gid: int
    #: why this user, said once at start (empty when it goes without saying)
    note: str = ''


def choose_user(running, folder, mounted):
    """Who runs the desktop (pure): from who started the container and who owns the folder,
    each a (uid, gid) pair, and whether the folder is mounted from outside."""
    if running[0] != 0:
        return DesktopUser(*running)
    folder_uid, folder_gid = folder
    note = '' if mounted else (
        'no folder of yours is mounted at %s: what you make there is lost when the container '
        'is removed (add -v "$PWD/catkin_ws:%s" to the docker run command)' % (WORKSPACE,
                                                                                WORKSPACE))
    if folder_uid == 0:
        return DesktopUser(IMAGE_UID, IMAGE_GID, note or (
            '%s belongs to root inside the container: running as uid %d (rootless Podman: add '
            '--userns=keep-id, so files are yours on the host)' % (WORKSPACE, IMAGE_UID)))
    return DesktopUser(folder_uid, folder_gid, note)


def is_mount_point(path, mountinfo='/proc/self/mountinfo'):
    """True when path is a mount point (a host folder or a volume given with -v)."""
    try:
        with open(mountinfo, encoding='utf-8') as f:
            return any(line.split()[4] == path for line in f if len(line.split()) > 4)
    except OSError:
        return False


def main(argv=None):
    args = sys.argv[1:] if argv is None else argv
    try:
        info = os.stat(WORKSPACE)
    except OSError as err:
        sys.exit('desktop: %s cannot be read: %s' % (WORKSPACE, err.strerror))
    user = choose_user((os.getuid(), os.getgid()), (info.st_uid, info.st_gid),
                       is_mount_point(WORKSPACE))
    if user.note:
        print('desktop: %s' % user.note, flush=True)
    if os.getuid() == 0:
        become(user)
    if not can_write(WORKSPACE):
        sys.exit('desktop: %s' % cannot_write_message(os.getuid(), info.st_uid))
    home = HOME if os.access(HOME, os.W_OK) else _scratch_home()
    env = dict(os.environ, HOME=home, USER=_name(), LOGNAME=_name())
    os.chdir('/workspace')
    os.execvpe('./ws', ['./ws', 'desktop', '--listen', '0.0.0.0', '--workspace', WORKSPACE]
               + args, env)


def can_write(folder):
    """True when this user can make a file in folder: tried, as Docker Desktop's shared folders
    let users write whatever their mode bits say."""
    try:
        fd, path = tempfile.mkstemp(prefix='.desktop-write-check-', dir=folder)
    except OSError:
        return False
    os.close(fd)
    os.unlink(path)
    return True


def cannot_write_message(uid, folder_uid):
    """What to do when the desktop's user cannot write to the mounted folder (pure)."""
    if folder_uid == 0:
        # Rootful Docker on Linux makes a missing host folder itself, as root.
        return ('%s belongs to root on your computer (Docker made it, as it did not exist), so '
                'the desktop (uid %d) cannot write to it: make the folder yourself before '
                '`docker run` (mkdir catkin_ws), or give it to yourself: sudo chown "$(id -u):'
                '$(id -g)" catkin_ws; with rootless Podman, add --userns=keep-id'
                % (WORKSPACE, uid))
    return ('uid %d cannot write to %s (the folder you mounted): give yourself write permission '
            'on it (chmod u+rwx catkin_ws)' % (uid, WORKSPACE))


def become(user):
    """Gives the image's student this uid and gid (so names and ~ stay right), gives it its
    home, then drops root for good."""
    current = pwd.getpwnam(USER)
    if (user.uid, user.gid) != (current.pw_uid, current.pw_gid):
        # -o: the host's ids may already name someone in the image (macOS's staff is gid 20).
        _run(['groupmod', '-o', '-g', str(user.gid), USER])
        _run(['usermod', '-o', '-u', str(user.uid), '-g', str(user.gid), USER])
    # The home, not the mounted folder in it (that one is the student's already).
    _run(['find', HOME, '-xdev', '-path', WORKSPACE, '-prune', '-o', '-exec', 'chown',
          '%d:%d' % (user.uid, user.gid), '{}', '+'])
    os.setgroups([])
    os.setgid(user.gid)
    os.setuid(user.uid)


def _run(argv):
    done = subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                          check=False)
    if done.returncode != 0:
        sys.exit('desktop: %s failed: %s' % (' '.join(argv), done.stderr.strip()))


def _scratch_home():
    return tempfile.mkdtemp(prefix='student-home-')


def _name():
    try:
        return pwd.getpwuid(os.getuid()).pw_name
    except KeyError:
        return USER


if __name__ == '__main__':
    main()
