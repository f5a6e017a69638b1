"""Stage 4.3's world-file syntax, rule for rule (libstage/worldfile.cc's tokenizer and parser).

What Stage accepts is accepted here, with the same meaning:
- tokens: `#` comments, words (a letter, then letters, digits and `.-_[]`), numbers (the
  characters `+-.0123456789` only: no exponent), "strings" on one line, `( ) [ ]`, blanks,
  line ends; any other character is a syntax error;
- `include "file"` inlines the file's tokens (a relative path is taken from the directory of
  the MAIN world file, as Stage does, even inside an included file) and ignores the rest of
  its line;
- `define NAME PARENT ( ... )`: the first definition of a name wins; an instance re-reads
  the definition's body, then its own, into one entity, so its properties override;
- a property's value (a number, a string or a tuple) must start on its own line; a tuple
  holds numbers and strings and ends on its line; a later property of the same name wins.
Entities are numbered in the order their `(` is read (0 is the file itself), parents before
children, as Stage loads them. Every property keeps its raw values and where it was written;
worldfile.Worldfile reads them as Stage's readers do.
"""
import os
import re
from dataclasses import dataclass, field

WORD, NUM, STRING, OPEN_ENTITY, CLOSE_ENTITY, OPEN_TUPLE, CLOSE_TUPLE, EOL, COMMENT = range(9)
_WORD_CHARS = re.compile(r'[A-Za-z0-9.\-_\[\]]*')
_NUM_CHARS = re.compile(r'[+\-.0-9]*')
_SINGLE = {'(': OPEN_ENTITY, ')': CLOSE_ENTITY, '[': OPEN_TUPLE, ']': CLOSE_TUPLE}


class WorldError(Exception):
    """A world that cannot be loaded; str() is one line, 'PATH:LINE: what is wrong'."""

    def __init__(self, path, line, what):
        where = '%s:%d' % (path, line) if line else str(path)
        super().__init__('%s: %s' % (where, what))
        self.path = path
        self.line = line
        self.what = what


@dataclass(slots=True)
class Token:
    kind: int
    text: str
    path: str
    line: int


def tokenize(path, main_dir=None, _chain=()):
    """The tokens of a world file with its includes inlined (blanks dropped)."""
    path = os.path.normpath(path)
    main_dir = os.path.dirname(path) if main_dir is None else main_dir
    real = os.path.realpath(path)
    if real in _chain:
        raise WorldError(path, None, 'include loop: the file includes itself')
    try:
        with open(path, 'rb') as f:
            text = f.read().decode('latin-1')
    except FileNotFoundError:
        raise WorldError(path, None, 'the world file does not exist') from None
    except OSError as e:
        raise WorldError(path, None, 'cannot read it: %s' % e.strerror) from None
    out = []
    i, n, line = 0, len(text), 1

    def add(kind, value):
        out.append(Token(kind, value, path, line))

    while i < n:
        ch = text[i]
        if ch == '#':
            j = i
            while j < n and text[j] not in '\r\n':
                j += 1
            add(COMMENT, text[i:j])
            i = j
        elif ch.isascii() and ch.isalpha():
            word = _WORD_CHARS.match(text, i + 1).group()
            word = ch + word
            i += len(word)
            add(WORD, word)
            if word == 'include':
                i = _include(text, i, path, line, main_dir, _chain + (real,), out)
                line += 1
        elif ch in '+-.0123456789':
            num = _NUM_CHARS.match(text, i).group()
            add(NUM, num)
            i += len(num)
        elif ch in ' \t':
            i += 1
        elif ch == '"':
            j = i + 1
            while j < n and text[j] not in '"\r\n':
                j += 1
            if j >= n or text[j] != '"':
                raise WorldError(path, line, 'syntax error: unterminated string constant')
            add(STRING, text[i + 1:j])
            i = j + 1
        elif ch in _SINGLE:
            add(_SINGLE[ch], ch)
            i += 1
        elif ch in '\r\n':
            # \r\n and \n\r are one line end, as Stage reads them
            i += 2 if text[i + 1:i + 2] == ('\n' if ch == '\r' else '\r') else 1
            add(EOL, '\n')
            line += 1
        else:
            raise WorldError(path, line, 'syntax error: unexpected character %r' % ch)
    return out


def _include(text, i, path, line, main_dir, chain, out):
    """Reads `include "file"` from text[i] on, appends the file's tokens to out; returns the
    index past the include's line (Stage ignores the rest of that line)."""
    n = len(text)
    if i >= n or text[i] not in ' \t':
        raise WorldError(path, line, 'syntax error in include statement (include "FILE")')
    while i < n and text[i] in ' \t':
        i += 1
    if i >= n or text[i] != '"':
        raise WorldError(path, line, 'syntax error in include statement (include "FILE")')
    j = text.find('"', i + 1)
    k = min(x for x in (text.find('\n', i + 1), text.find('\r', i + 1), n) if x >= 0)
    if j < 0 or j > k:
        raise WorldError(path, line, 'syntax error: unterminated string constant')
    name = text[i + 1:j]
    out.append(Token(STRING, name, path, line))
    out.append(Token(EOL, '\n', path, line))
    target = name if name.startswith(('/', '~')) else os.path.join(main_dir, name)
    try:
        out.extend(tokenize(target, main_dir, chain))
    except WorldError as e:
        if e.path == os.path.normpath(target) and e.line is None:
            raise WorldError(path, line, 'cannot include %s: %s' % (target, e.what)) from None
        raise
    end = text.find('\n', j)
    return n if end < 0 else end + 1


@dataclass(eq=False, slots=True)
class Prop:
    """One written property: its raw values (number or string texts), where, and whether read."""

    name: str
    values: list
    path: str
    line: int
    used: bool = False


@dataclass(eq=False, slots=True)
class Entity:
    """One entity as Stage numbers them: its type as written after define chains resolve to a
    type Stage knows (e.g. 'position' for an `erratic(...)`), its parent entity's index."""

    index: int
    parent: int
    kind: str
    path: str
    line: int
    props: dict = field(default_factory=dict)
    children: list = field(default_factory=list)


def parse(path):
    """The entities of the world file at path (its includes inlined), entity 0 the file
    itself; WorldError at the first syntax error."""
    return _Parser(path).entities


class _Parser:
    """Worldfile::ParseTokens and friends, over the tokens of one world file."""

    def __init__(self, path):
        self.path = path
        self.tokens = tokenize(path)
        self.macros = {}
        # a macro's expansion, kept to be copied for its next instances (a swarm world has
        # thousands): what it created, keyed by where its body starts and by how many
        # macros were defined then (a later define could change what its body means)
        self._expansions = {}
        self.entities = [Entity(0, -1, '', path, 0)]
        self._parse()

    def _error(self, i, what):
        t = self.tokens[min(i, len(self.tokens) - 1)] if self.tokens else None
        return WorldError(t.path if t else self.path, t.line if t else None, what)

    def _parse(self):
        toks = self.tokens
        i = 0
        while i < len(toks):
            t = toks[i]
            if t.kind == WORD:
                if t.text == 'include':
                    i = self._parse_include(i)
                elif t.text == 'define':
                    i = self._parse_define(i)
                else:
                    i = self._parse_word(0, i)
            elif t.kind not in (COMMENT, EOL):
                raise self._error(i, 'syntax error: unexpected "%s" at the top level' % t.text)
            i += 1

    def _parse_include(self, i):
        for j in range(i + 1, len(self.tokens)):
            kind = self.tokens[j].kind
            if kind == EOL:
                return j
            if kind != STRING:
                raise self._error(j, 'syntax error in include statement')
        raise self._error(i, 'incomplete include statement')

    def _parse_define(self, i):
        names = []
        depth = 0
        for j in range(i + 1, len(self.tokens)):
            t = self.tokens[j]
            if t.kind == WORD and depth == 0:
                if len(names) == 2:
                    raise self._error(j, 'extra tokens in macro definition (define NAME'
                                      ' PARENT ( ... ))')
                names.append(j)
            elif t.kind == OPEN_ENTITY:
                if len(names) < 2:
                    raise self._error(j, 'missing name in macro definition (define NAME'
                                      ' PARENT ( ... ))')
                depth += 1
            elif t.kind == CLOSE_ENTITY:
                depth -= 1
                if depth == 0:
                    name = self.tokens[names[0]].text
                    # std::map::insert: the first definition of a name is kept
                    self.macros.setdefault(name, names[1])
                    return j
                if depth < 0:
                    raise self._error(j, "misplaced ')'")
        raise self._error(i, "missing ')' in macro definition")

    def _parse_word(self, entity, i):
        """A word in an entity: a child entity (word then '(') or a property."""
        for j in range(i + 1, len(self.tokens)):
            kind = self.tokens[j].kind
            if kind in (COMMENT, EOL):
                continue
            if kind == OPEN_ENTITY:
                return self._parse_entity(entity, i)
            if kind in (NUM, STRING, OPEN_TUPLE):
                return self._parse_property(entity, i)
            raise self._error(j, 'syntax error: "%s" is neither a property with a value nor'
                              ' an entity' % self.tokens[i].text)
        raise self._error(i, 'syntax error: property %s has no value' % self.tokens[i].text)

    def _parse_entity(self, entity, i):
        toks = self.tokens
        name = toks[i].text
        start = self.macros.get(name)
        if start is not None:
            created = len(self.entities)
            self._expand(entity, start)
            if len(self.entities) == created:
                raise self._error(i, 'macro %s defines no entity' % name)
            entity = created
            # messages about the instance name the instance, not its define
            self.entities[entity].path = toks[i].path
            self.entities[entity].line = toks[i].line
        j = i + 1
        while j < len(toks):
            kind = toks[j].kind
            if kind == OPEN_ENTITY:
                if start is None:
                    entity = self._add_entity(entity, name, toks[i])
            elif kind == WORD:
                j = self._parse_word(entity, j)
            elif kind == CLOSE_ENTITY:
                return j
            elif kind not in (COMMENT, EOL):
                raise self._error(j, 'syntax error: unexpected "%s" in %s( )'
                                  % (toks[j].text, name))
            j += 1
        raise self._error(i, "missing ')' for %s( )" % name)

    def _expand(self, parent, start):
        """A macro's body parsed as a child of parent: the first time by _parse_entity,
        then as a copy of what that made (the same entities, properties and places)."""
        created = len(self.entities)
        key = (start, len(self.macros))
        made = self._expansions.get(key)
        if made is None:
            self._parse_entity(parent, start)
            self._expansions[key] = [
                (e.parent - created if e.parent >= created else -1, e.kind, e.path, e.line,
                 [(q.name, q.values, q.path, q.line) for q in e.props.values()])
                for e in self.entities[created:]]
            return
        for up, kind, path, line, props in made:
            ent = Entity(len(self.entities), parent if up < 0 else created + up, kind, path,
                         line, {name: Prop(name, values, where, at)
                                for name, values, where, at in props})
            self.entities.append(ent)
            self.entities[ent.parent].children.append(ent.index)

    def _add_entity(self, parent, kind, tok):
        ent = Entity(len(self.entities), parent, kind, tok.path, tok.line)
        self.entities.append(ent)
        self.entities[parent].children.append(ent.index)
        return ent.index

    def _parse_property(self, entity, i):
        toks = self.tokens
        name = toks[i]
        j = i + 1
        if j < len(toks) and toks[j].kind in (NUM, STRING):
            self._add_property(entity, name, [toks[j].text])
            return j
        if j < len(toks) and toks[j].kind == OPEN_TUPLE:
            values = []
            end = j + 1
            while end < len(toks) and toks[end].kind != CLOSE_TUPLE:
                if toks[end].kind not in (NUM, STRING):
                    raise self._error(end, 'syntax error in the tuple of %s: a tuple holds'
                                      ' numbers and strings and ends on its line' % name.text)
                values.append(toks[end].text)
                end += 1
            # (a tuple still open at the end of the file ends there, as in Stage)
            self._add_property(entity, name, values)
            return min(end, len(toks) - 1)
        raise self._error(j, 'syntax error: the value of %s must be on its line' % name.text)

    def _add_property(self, entity, tok, values):
        self.entities[entity].props[tok.text] = Prop(tok.text, values, tok.path, tok.line)
