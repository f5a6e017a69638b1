"""Stage 4.3's world-file readers, rule for rule (libstage/worldfile.cc), with better messages.

A world file is parsed as Stage parses it (worldfile_syntax: tokens, includes, defines,
entities, properties); its properties are then read as Stage's readers read them:
- values are read as C's atof/atoi read them ("1.5" as an int is 1, a word is 0); a tuple is
  read as far as a property needs (extra values are ignored: here with a WARN), and one
  shorter than needed is an error (Stage exits);
- lengths in metres (`unit_length` m, cm or mm) and angles in degrees (`unit_angle`).
Every property remembers whether anything read it: Stage's "defined but not used" warnings.
"""
import functools
import os
import re

from .pose import DEG
from .worldfile_syntax import WorldError, parse

__all__ = ['Worldfile', 'WorldError', 'c_atof', 'c_atoi']

_ATOI = re.compile(r'[ \t\n\v\f\r]*([+-]?[0-9]+)')
_ATOF = re.compile(r'[ \t\n\v\f\r]*([+-]?(?:0[xX](?:[0-9a-fA-F]+\.?[0-9a-fA-F]*|\.[0-9a-fA-F]+)'
                   r'(?:[pP][+-]?[0-9]+)?|(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?'
                   r'|inf(?:inity)?|nan))', re.IGNORECASE)


@functools.lru_cache(maxsize=4096)
def c_atoi(text):
    """C's atoi: leading blanks, a sign, digits; 0 when there are none ('1.9' gives 1)."""
    m = _ATOI.match(text)
    return int(m.group(1)) if m else 0


@functools.lru_cache(maxsize=4096)
def c_atof(text):
    """C's atof (strtod): the longest number at the start ('0.5m' gives 0.5), else 0.0."""
    m = _ATOF.match(text)
    if not m:
        return 0.0
    s = m.group(1)
    if 'x' in s.lower() and 'n' not in s.lower():
        sign = -1.0 if s.startswith('-') else 1.0
        body = s.lstrip('+-')
        return sign * float.fromhex(body if 'p' in body.lower() else body + 'p0')
    return float(s)


class Worldfile:
    """A parsed world file: entities, properties and Stage's typed readers."""

    def __init__(self, path):
        self.path = os.path.normpath(path)
        self.entities = parse(self.path)
        self.warnings = []
        self.unit_length = 1.0
        self.unit_angle = DEG
        unit = self.read_string(0, 'unit_length', 'm')
        self.unit_length = {'m': 1.0, 'cm': 0.01, 'mm': 0.001}.get(unit, 1.0)
        unit = self.read_string(0, 'unit_angle', 'degrees')
        self.unit_angle = {'degrees': DEG, 'radians': 1.0}.get(unit, DEG)
        if self.read_int(0, 'test', 0) != 0:
            raise WorldError(self.path, None, 'this is a test file ("test" is set); Stage quits')

    # ---- Stage's readers (ReadString, ReadInt, ReadFloat, ReadTuple, ...) ------------------
    def prop(self, entity, name):
        """The Prop or None; does not mark it used (Stage's PropertyExists)."""
        return self.entities[entity].props.get(name)

    def exists(self, entity, name):
        return name in self.entities[entity].props

    def _value(self, p, k):
        p.used = True
        return p.values[k]

    def read_values(self, entity, name):
        """Every value of the property as written (number or string texts), or None when it
        is not there; each value read is marked used, as Stage's readers mark them."""
        p = self.prop(entity, name)
        return None if p is None else [self._value(p, k) for k in range(len(p.values))]

    def read_string(self, entity, name, default):
        p = self.prop(entity, name)
        return default if p is None else self._value(p, 0)

    def read_int(self, entity, name, default):
        p = self.prop(entity, name)
        return default if p is None else c_atoi(self._value(p, 0))

    def read_float(self, entity, name, default):
        p = self.prop(entity, name)
        return default if p is None else c_atof(self._value(p, 0))

    def read_length(self, entity, name, default):
        return self.read_float(entity, name, default / self.unit_length) * self.unit_length

    def read_angle(self, entity, name, default):
        return self.read_float(entity, name, default / self.unit_angle) * self.unit_angle

    def read_tuple(self, entity, name, fmt):
        """The first len(fmt) values converted per character ('l' length, 'a' angle, 'f'
        float, 'i' int, 's' string), or None when the property is not there."""
        p = self.prop(entity, name)
        if p is None:
            return None
        if len(p.values) < len(fmt):
            raise WorldError(p.path, p.line, 'property %s needs %d values, got %d (Stage exits:'
                             ' "reading tuple %s index 0 to %d - tuple has length %d")'
                             % (name, len(fmt), len(p.values), name, len(fmt) - 1,
                                len(p.values)))
        if len(p.values) > len(fmt):
            self.warn(p, 'property %s has %d values; Stage reads the first %d'
                      % (name, len(p.values), len(fmt)))
        p.used = True
        out = []
        for c, v in zip(fmt, p.values, strict=False):     # values beyond fmt: not read
            if c == 'l':
                out.append(c_atof(v) * self.unit_length)
            elif c == 'a':
                out.append(c_atof(v) * self.unit_angle)
            elif c == 'f':
                out.append(c_atof(v))
            elif c == 'i':
                out.append(c_atoi(v))
            else:
                out.append(v)
        return out

    def warn(self, p, what):
        self.warnings.append('%s:%d: %s' % (p.path, p.line, what))

    def unused_warnings(self):
        """Stage's warnings for properties nothing read, in file order, each line once."""
        seen = set()
        out = []
        for ent in self.entities:
            for p in ent.props.values():
                key = (p.path, p.line, p.name)
                if not p.used and key not in seen:
                    seen.add(key)
                    out.append(key)
        out.sort()
        return ['%s:%d: property %s is defined but not used' % k for k in out]
