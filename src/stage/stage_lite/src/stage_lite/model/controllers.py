"""Starting the controllers a world names, as Stage does (LoadControllerModule, then
InitControllers once the world is loaded); no rospy.

`ctrl "name args"` on a model: the string's first word names the controller, the whole
string is its CtrlArgs.worldfile (`ctrl "source 5"`: a source holding 5 flags); a model may
name several (`ctrl [ "a" "b" ]`). Stage looks for `name.so` in the folders of STAGEPATH,
then in its own plugin folder; here:
1. `name.py` in a folder of STAGEPATH (colon-separated): your own controller, in Python;
2. Stage's own controllers, ported: the module `stage_lite.controllers.name`.
Its `init(model, args)` is called with the model (stage_api) and a CtrlArgs, every model in
Stage's order (World.stage_order: file order unless a real run's order is given), each
model's controllers in the order named: it subscribes what it reads and
adds the callbacks that drive it. What Stage does with a plugin it cannot use (it exits) is
one WorldError naming the world file's line: a controller not found, one that does not
import, has no init, or raises in it. A callback that raises later is reported once, with
that line, and removed: the other models go on.
"""
import importlib
import importlib.util
import os
import sys
import traceback

from .stage_api import CtrlArgs, api_of
from .worldfile import WorldError

BUILTIN_PACKAGE = 'stage_lite.controllers'


def search_path(environ=None):
    """The folders of STAGEPATH, in order (empty entries skipped)."""
    value = (os.environ if environ is None else environ).get('STAGEPATH', '')
    return [d for d in value.split(':') if d]


def find(name, environ=None):
    """(where it was found, the loaded module) for a controller name; WorldError-free:
    raises LookupError (not found) or ImportError (found, does not import)."""
    for folder in search_path(environ):
        path = os.path.join(folder, name + '.py')
        if os.path.isfile(path):
            # loaded once per process, as Stage opens a plugin once: its globals are shared
            # by every model (and world) that names it
            key = 'stage_ctrl_' + name
            module = sys.modules.get(key)
            if module is not None and getattr(module, '__file__', None) == path:
                return path, module
            spec = importlib.util.spec_from_file_location(key, path)
            module = importlib.util.module_from_spec(spec)
            try:
                spec.loader.exec_module(module)
            except Exception as err:
                raise ImportError('%s: %s' % (path, describe(err))) from None
            sys.modules[key] = module
            return path, module
    if name.isidentifier():
        try:
            return BUILTIN_PACKAGE + '.' + name, importlib.import_module(
                BUILTIN_PACKAGE + '.' + name)
        except ModuleNotFoundError as err:
            if err.name != BUILTIN_PACKAGE + '.' + name:
                raise ImportError('%s: %s' % (name, describe(err))) from None
    raise LookupError(name)


def builtin_names():
    """Stage's own controllers ported here."""
    package = importlib.import_module(BUILTIN_PACKAGE)
    folder = os.path.dirname(package.__file__)
    return sorted(f[:-3] for f in os.listdir(folder)
                  if f.endswith('.py') and not f.startswith('_'))


def start(world, environ=None):
    """Every model's controllers, loaded and initialised in Stage's order; WorldError for the
    first that cannot be used. Returns whether one of them is your own (from STAGEPATH)."""
    pending = []
    own = False
    stagepath = (os.environ if environ is None else environ).get('STAGEPATH', 'unset')
    for model in world.stage_order:      # Stage's InitControllers: World::models' order
        for text, path, line in model.ctrl:
            words = text.split()
            if not words:
                raise WorldError(path, line, 'ctrl "%s": no controller named' % text)
            try:
                where, module = find(words[0], environ)
            except LookupError:
                raise WorldError(path, line, 'ctrl "%s": no controller "%s": not in STAGEPATH'
                                 ' (%s) nor among Stage\'s own (%s)'
                                 % (text, words[0], stagepath, ', '.join(builtin_names()))
                                 ) from None
            except ImportError as err:
                raise WorldError(path, line, 'ctrl "%s": the controller does not load: %s'
                                 % (text, err)) from None
            init = getattr(module, 'init', None)
            if not callable(init):
                raise WorldError(path, line, 'ctrl "%s": %s has no init(model, args)'
                                 % (text, where))
            pending.append((model, text, path, line, init))
            own = own or not where.startswith(BUILTIN_PACKAGE + '.')
    scheduler = world.scheduler
    scheduler.on_error = lambda owner, model, err: world.log(
        '%s:%d: ctrl "%s" on %s: %s; its callback is removed, the other models go on'
        % (owner.path, owner.line, owner.text, model.token, describe(err)))
    for model, text, path, line, init in pending:
        scheduler.owner = Owner(text, path, line)
        try:
            init(api_of(world, model), CtrlArgs(text, world.ctrlargs))
        except Exception as err:
            raise WorldError(path, line, 'ctrl "%s" on %s: its init failed: %s'
                             % (text, model.token, describe(err))) from None
        finally:
            scheduler.owner = None
    return own


class Owner:
    """A controller as the world file names it: its errors name that line."""

    def __init__(self, text, path, line):
        self.text = text
        self.path = path
        self.line = line


def describe(err):
    """The error and the last line of code that raised it."""
    frames = traceback.extract_tb(err.__traceback__)
    where = ''
    if frames:
        last = frames[-1]
        where = ' (%s:%d, in %s)' % (last.filename, last.lineno, last.name)
    return '%s: %s%s' % (type(err).__name__, err, where)


def default_log(text):
    """Where a world's run-time errors go without a node: stderr, as Stage prints them."""
    sys.stderr.write('[ERROR] %s\n' % text)
