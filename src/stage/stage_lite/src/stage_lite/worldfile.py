"""Stage 4 world-file reader: tokens, entities, `define` chains, `include`, unit conversion.

The syntax (Stage 4 `worldfile.cc`): `#` comments, words, numbers, "strings", tuples `[ ]`,
entities `type ( ... )` (nested), `define NEW PARENT ( defaults )` and `include "file"`
(relative to the including file). Every property remembers its file and line, so a message can
name them, and whether anything read it, so unread ones draw Stage's "defined but not used"
warning. Angles are written in degrees and handed out in radians.
"""

import math
import os
import re
from dataclasses import dataclass, field

# Stage 4's model types. Ones this stand-in does not simulate are loaded as plain bodies.
BUILTIN_TYPES = ('model', 'position', 'ranger', 'camera', 'fiducial', 'blobfinder', 'gripper',
                 'actuator', 'blinkenlight', 'lightindicator')
# Entities that are not models: the GUI window, a ranger's sensor, a model's polygon block.
SPECIAL_TYPES = ('window', 'sensor', 'block')

_TOKEN = re.compile(r'''
    (?P<ws>[ \t\r\f\v]+)
  | (?P<nl>\n)
  | (?P<comment>\#[^\n]*)
  | (?P<string>"[^"\n]*")
  | (?P<open>[(\[])
  | (?P<close>[)\]])
  | (?P<number>[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?![A-Za-z_]))
  | (?P<word>[A-Za-z_][A-Za-z0-9_.\-/]*(?:\[\d+\])?)
  | (?P<bad>"[^"\n]*|.)
''', re.VERBOSE)


class WorldError(Exception):
    """A world that cannot be loaded; str() is one line, 'PATH:LINE: what is wrong'."""

    def __init__(self, path, line, what):
        where = '%s:%d' % (path, line) if line else str(path)
        super().__init__('%s: %s' % (where, what))
        self.path = path
        self.line = line
        self.what = what


@dataclass
class Token:
    kind: str
    text: str
    path: str
    line: int


@dataclass(eq=False)
class Prop:
    """One written property: its values (numbers as float, strings and words as str)."""

    name: str
    values: list
    path: str
    line: int
    used: bool = False


@dataclass(eq=False)
class Entity:
    """A model (or window/sensor/block) as written, after `define` chains are resolved.

    `kind` is the built-in type at the root of the define chain, `declared` the type as
    written (e.g. 'erratic'). Properties of defines are shared objects, so reading one marks
    it used for every instance.
    """

    kind: str
    declared: str
    path: str
    line: int
    props: dict = field(default_factory=dict)
    children: list = field(default_factory=list)

    def has(self, name):
        return name in self.props

    def prop(self, name):
        """The Prop (marked used) or None."""
        p = self.props.get(name)
        if p is not None:
            p.used = True
        return p

    def where(self, name=None):
        p = self.props.get(name) if name else None
        return (p.path, p.line) if p else (self.path, self.line)

    def error(self, name, what):
        path, line = self.where(name)
        return WorldError(path, line, what)

    def number(self, name, default):
        p = self.prop(name)
        if p is None:
            return default
        if len(p.values) != 1 or not isinstance(p.values[0], float):
            raise WorldError(p.path, p.line, 'property %s needs one number, got %s'
                             % (name, _show(p.values)))
        return p.values[0]

    def text(self, name, default):
        p = self.prop(name)
        if p is None:
            return default
        if len(p.values) != 1:
            raise WorldError(p.path, p.line, 'property %s needs one value, got %s'
                             % (name, _show(p.values)))
        v = p.values[0]
        return v if isinstance(v, str) else _fmt(v)

    def tuple(self, name, default, angles=()):
        """A tuple property; missing trailing elements keep `default`'s; the indices in
        `angles` are degrees in the file and radians here."""
        p = self.prop(name)
        out = list(default)
        if p is None:
            return tuple(out)
        vals = p.values
        if len(vals) > len(out) or not all(isinstance(v, float) for v in vals):
            raise WorldError(p.path, p.line, 'property %s needs up to %d numbers, got %s'
                             % (name, len(out), _show(vals)))
        for i, v in enumerate(vals):
            out[i] = math.radians(v) if i in angles else v
        return tuple(out)

    def use_all(self):
        for p in self.props.values():
            p.used = True


def _fmt(v):
    return ('%d' % v) if float(v).is_integer() else repr(v)


def _show(values):
    return '[' + ' '.join(v if isinstance(v, str) else _fmt(v) for v in values) + ']'


def tokenize(text, path):
    """Tokens of one file; comments and white space dropped."""
    tokens = []
    line = 1
    for m in _TOKEN.finditer(text):
        kind = m.lastgroup
        s = m.group()
        if kind == 'nl':
            line += 1
        elif kind in ('ws', 'comment'):
            pass
        elif kind == 'bad':
            what = 'unterminated string' if s.startswith('"') else 'unexpected character %r' % s
            raise WorldError(path, line, 'syntax error: ' + what)
        else:
            tokens.append(Token(kind, s, path, line))
    return tokens


@dataclass
class ParsedWorld:
    """The top level of a world file: its properties and model entities."""

    path: str
    top: Entity
    window: object = None          # the window Entity or None
    models: list = field(default_factory=list)
    all_entities: list = field(default_factory=list)

    def unused_warnings(self):
        """Stage's warnings for properties nothing read, in file order, each once."""
        seen = set()
        out = []
        for ent in self.all_entities:
            for p in ent.props.values():
                key = (p.path, p.line, p.name)
                if not p.used and key not in seen:
                    seen.add(key)
                    out.append((p.path, p.line, '%s:%d: property %s is defined but not used'
                                % (p.path, p.line, p.name)))
        out.sort(key=lambda t: (t[0], t[1]))
        return [w for _, _, w in out]


@dataclass
class _Define:
    name: str
    parent: str
    kind: str
    props: dict
    children: list          # template Entities


class _Parser:
    def __init__(self):
        self.defines = {}
        self.include_stack = []
        self.all_entities = []

    def parse_file(self, path, top, line_of_include=None, includer=None):
        path = os.path.normpath(path)
        real = os.path.realpath(path)
        if real in self.include_stack:
            raise WorldError(includer, line_of_include, 'include loop: %s includes itself'
                             % path)
        try:
            with open(path, encoding='utf-8', errors='replace') as f:
                text = f.read()
        except FileNotFoundError:
            if includer:
                raise WorldError(includer, line_of_include, 'included file %s does not exist'
                                 % path) from None
            raise WorldError(path, None, 'the world file does not exist') from None
        except OSError as e:
            raise WorldError(includer or path, line_of_include,
                             'cannot read %s: %s' % (path, e.strerror)) from None
        self.include_stack.append(real)
        self.tokens = tokenize(text, path)
        self.pos = 0
        self._body(top, path, at_top=True)
        self.include_stack.pop()

    def _peek(self, k=0):
        i = self.pos + k
        return self.tokens[i] if i < len(self.tokens) else None

    def _next(self, path, what):
        t = self._peek()
        if t is None:
            last = self.tokens[-1].line if self.tokens else 1
            raise WorldError(path, last, 'syntax error: end of file while reading ' + what)
        self.pos += 1
        return t

    def _body(self, ent, path, at_top):
        """Statements until ')' (entity) or end of file (top level)."""
        while True:
            t = self._peek()
            if t is None:
                if at_top:
                    return
                last = self.tokens[-1].line if self.tokens else 1
                raise WorldError(path, last, 'syntax error: missing ")" for %s entity opened'
                                 ' at line %d' % (ent.declared, ent.line))
            if t.kind == 'close' and t.text == ')' and not at_top:
                self.pos += 1
                return
            if t.kind != 'word':
                raise WorldError(t.path, t.line, 'syntax error: unexpected %s' % t.text)
            self.pos += 1
            nxt = self._peek()
            if t.text == 'include' and nxt is not None and nxt.kind == 'string':
                self.pos += 1
                self._include(ent, t, nxt)
            elif t.text == 'define':
                self._define(t)
            elif nxt is not None and nxt.kind == 'open' and nxt.text == '(':
                self.pos += 1
                child = self._entity(t)
                ent.children.append(child)
            else:
                self._property(ent, t)

    def _include(self, ent, tok, name_tok):
        name = name_tok.text[1:-1]
        target = os.path.join(os.path.dirname(tok.path), name)
        tokens, pos = self.tokens, self.pos
        self.parse_file(target, ent, tok.line, tok.path)
        self.tokens, self.pos = tokens, pos

    def _define(self, tok):
        name = self._next(tok.path, 'a define')
        parent = self._next(tok.path, 'a define')
        opener = self._next(tok.path, 'a define')
        if name.kind != 'word' or parent.kind != 'word' or opener.text != '(':
            raise WorldError(tok.path, tok.line, 'syntax error: expected "define NAME PARENT ('
                             ' ... )"')
        kind, props, children = self._resolve_type(parent)
        tmpl = Entity(kind, name.text, tok.path, tok.line, dict(props), list(children))
        self._body(tmpl, tok.path, at_top=False)
        self.defines[name.text] = _Define(name.text, parent.text, kind, tmpl.props,
                                          tmpl.children)

    def _resolve_type(self, tok):
        if tok.text in self.defines:
            d = self.defines[tok.text]
            return d.kind, d.props, d.children
        if tok.text in BUILTIN_TYPES or tok.text in SPECIAL_TYPES:
            return tok.text, {}, []
        raise WorldError(tok.path, tok.line, 'unknown model type "%s"' % tok.text)

    def _entity(self, tok):
        kind, props, children = self._resolve_type(tok)
        ent = Entity(kind, tok.text, tok.path, tok.line, dict(props))
        ent.children = [_instantiate(c) for c in children]
        self._body(ent, tok.path, at_top=False)
        return ent

    def _property(self, ent, tok):
        t = self._next(tok.path, 'property %s' % tok.text)
        if t.kind == 'open' and t.text == '[':
            values = []
            while True:
                v = self._next(tok.path, 'tuple of %s' % tok.text)
                if v.kind == 'close' and v.text == ']':
                    break
                values.append(self._value(v, tok.text))
        else:
            values = [self._value(t, tok.text)]
        ent.props[tok.text] = Prop(tok.text, values, tok.path, tok.line)

    @staticmethod
    def _value(t, name):
        if t.kind == 'number':
            return float(t.text)
        if t.kind == 'string':
            return t.text[1:-1]
        if t.kind == 'word':
            return t.text
        raise WorldError(t.path, t.line, 'syntax error: unexpected "%s" in property %s'
                         % (t.text, name))


def _instantiate(tmpl):
    """A fresh entity from a define's child template (props shared, tree copied)."""
    ent = Entity(tmpl.kind, tmpl.declared, tmpl.path, tmpl.line, dict(tmpl.props))
    ent.children = [_instantiate(c) for c in tmpl.children]
    return ent


def parse(path):
    """Reads a world file (and its includes) into a ParsedWorld; raises WorldError."""
    p = _Parser()
    top = Entity('world', 'world', path, 0)
    p.parse_file(path, top)
    world = ParsedWorld(path, top)
    stack = [top]
    while stack:
        ent = stack.pop()
        world.all_entities.append(ent)
        stack.extend(reversed(ent.children))
    world.all_entities.sort(key=lambda e: (e.path, e.line))
    for child in top.children:
        if child.kind == 'window':
            world.window = child
        elif child.kind in ('sensor', 'block'):
            raise WorldError(child.path, child.line, '%s( ) belongs inside a model'
                             % child.declared)
        else:
            world.models.append(child)
    return world
