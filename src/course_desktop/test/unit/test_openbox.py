"""course_desktop.openbox: Debian's openbox configuration, edited for the desktop."""
import os
import xml.etree.ElementTree as ET

import pytest
from course_desktop.openbox import (
    DEBIAN_RC,
    NEW_TERMINAL_KEY,
    OpenboxConfigError,
    openbox_config,
    openbox_menu,
)

NS = {'ob': 'http://openbox.org/3.4/rc'}
COMMAND = "xterm -title 'Terminal: course workspace' -e bash --rcfile '/a b/rc' -i"
BASE = '''<?xml version="1.0"?>
<openbox_config xmlns="http://openbox.org/3.4/rc">
<desktops>
  <number>4</number>
</desktops>
<keyboard>
  <keybind key="A-Tab"><action name="NextWindow"/></keybind>
</keyboard>
<mouse>
  <context name="Root"><mousebind button="Right" action="Press">
    <action name="ShowMenu"><menu>root-menu</menu></action></mousebind></context>
</mouse>
<menu>
  <file>/var/lib/openbox/debian-menu.xml</file>
  <file>menu.xml</file>
  <hideDelay>200</hideDelay>
</menu>
</openbox_config>
'''


def parsed(text):
    return ET.fromstring(text.encode())


def test_one_desktop_the_terminal_key_and_only_our_menu():
    root = parsed(openbox_config(COMMAND, '/run/x/menu.xml', base=BASE))
    assert root.find('ob:desktops/ob:number', NS).text == '1'
    keys = {k.get('key'): k for k in root.findall('ob:keyboard/ob:keybind', NS)}
    assert keys[NEW_TERMINAL_KEY].find('ob:action/ob:command', NS).text == COMMAND
    assert 'A-Tab' in keys  # Debian's own keys stay
    assert [f.text for f in root.findall('ob:menu/ob:file', NS)] == ['/run/x/menu.xml']
    assert root.find('ob:menu/ob:hideDelay', NS).text == '200'
    # the <menu> inside a mouse binding is not the menu section
    assert root.find('.//ob:mousebind/ob:action/ob:menu', NS).text == 'root-menu'


def test_a_base_without_a_section_is_a_clear_error():
    with pytest.raises(OpenboxConfigError, match='keyboard'):
        openbox_config(COMMAND, '/m.xml', base=BASE.replace('<keyboard>', '<keys>'))


@pytest.mark.skipif(not os.path.exists(DEBIAN_RC), reason='openbox is not installed')
def test_debians_own_rc_xml_takes_the_edits():
    root = parsed(openbox_config(COMMAND, '/run/x/menu.xml'))
    assert root.find('ob:desktops/ob:number', NS).text == '1'
    assert [f.text for f in root.findall('ob:menu/ob:file', NS)] == ['/run/x/menu.xml']


def test_the_menu_opens_the_workspace_terminal():
    menu = ET.fromstring(openbox_menu(COMMAND).encode())
    commands = [c.text for c in menu.iter('{http://openbox.org/3.4/menu}command')]
    assert commands == [COMMAND]
