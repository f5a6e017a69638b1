"""openbox's configuration for the desktop: Debian's own, with the workspace's terminal on
Ctrl+Alt+T and on the desktop's menu, and one virtual desktop (pure: text in, text out).

Debian's rc.xml keeps openbox's usual mouse and keys (drag a title bar, Alt+Tab, ...); only
what a student would trip over changes: four virtual desktops that the mouse wheel flips
through on the background, and a menu whose terminal lacks the workspace.
"""
import re
from xml.sax.saxutils import escape, quoteattr

DEBIAN_RC = '/etc/xdg/openbox/rc.xml'
NEW_TERMINAL_KEY = 'C-A-t'  # Ubuntu's and most desktops' "new terminal"


class OpenboxConfigError(ValueError):
    """Debian's rc.xml lacks a section the desktop edits (a new openbox release?)."""


def openbox_config(terminal_command, menu_path, base=None):
    """rc.xml: `base` (Debian's rc.xml when None) with one desktop, the terminal key and
    only the desktop's menu file."""
    if base is None:
        with open(DEBIAN_RC, encoding='utf-8') as f:
            base = f.read()
    text = _sub_once(r'(^<desktops>.*?<number>)\s*\d+\s*(</number>)', r'\g<1>1\g<2>', base,
                     'desktops/number')
    keybind = ('<keyboard>\n  <keybind key=%s>\n    <action name="Execute"><command>%s'
               '</command></action>\n  </keybind>' % (quoteattr(NEW_TERMINAL_KEY),
                                                    escape(terminal_command)))
    text = _sub_once(r'^<keyboard>', lambda _: keybind, text, 'keyboard')
    # The top-level <menu> section's <file> entries name Debian's menus: keep its settings,
    # list only ours.
    return _sub_once(r'^(<menu>)(.*?)(^</menu>)',
                     lambda m: '%s\n  <file>%s</file>%s%s' % (
                         m.group(1), escape(menu_path),
                         re.sub(r'\s*<file>.*?</file>', '', m.group(2)), m.group(3)),
                     text, 'menu')


def openbox_menu(terminal_command):
    """menu.xml: the right-click menu on the desktop's background."""
    return '''<?xml version="1.0" encoding="UTF-8"?>
<openbox_menu xmlns="http://openbox.org/3.4/menu">
<menu id="root-menu" label="Course desktop">
  <item label="Terminal (Ctrl+Alt+T)">
    <action name="Execute"><command>%s</command></action>
  </item>
  <separator/>
  <item label="Reconfigure openbox"><action name="Reconfigure"/></item>
</menu>
</openbox_menu>
''' % escape(terminal_command)


def _sub_once(pattern, replacement, text, what):
    new, count = re.subn(pattern, replacement, text, count=1, flags=re.DOTALL | re.MULTILINE)
    if count != 1:
        raise OpenboxConfigError('openbox\'s rc.xml has no %s section to edit' % what)
    return new
