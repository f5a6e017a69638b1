"""Unit tests of course_common.graph_names: roscpp's name validation, namespace normalisation."""

import pytest
from course_common.graph_names import graph_name_error, normalize_namespace, validate_graph_name


@pytest.mark.parametrize('name', ['turtle1', '/abs', 'grp/t', '~priv', 'a_b', 'A9', 'x//y', ''])
def test_valid_names(name):
    assert graph_name_error(name) is None
    validate_graph_name(name)


@pytest.mark.parametrize('name, message', [
    ('my turtle', 'Character [ ] at element [2] is not valid in Graph Resource Name '
                  '[my turtle].  Valid characters are a-z, A-Z, 0-9, / and _.'),
    ('1abc', 'Character [1] is not valid as the first character in Graph Resource Name '
             '[1abc].  Valid characters are a-z, A-Z, / and in some cases ~.'),
    ('_u', 'Character [_] is not valid as the first character in Graph Resource Name [_u].  '
           'Valid characters are a-z, A-Z, / and in some cases ~.'),
    ('a-b', 'Character [-] at element [1] is not valid in Graph Resource Name [a-b].  '
            'Valid characters are a-z, A-Z, 0-9, / and _.'),
    ('a~b', 'Character [~] at element [1] is not valid in Graph Resource Name [a~b].  '
            'Valid characters are a-z, A-Z, 0-9, / and _.'),
    ('\u00e9t\u00e9', 'Character [\u00e9] is not valid as the first character in Graph Resource '
                      'Name [\u00e9t\u00e9].  Valid characters are a-z, A-Z, / and in some '
                      'cases ~.'),
])
def test_invalid_names_have_roscpp_messages(name, message):
    assert graph_name_error(name) == message
    with pytest.raises(ValueError) as err:
        validate_graph_name(name)
    assert str(err.value) == message


@pytest.mark.parametrize('namespace, expected', [
    ('/', '/'), ('', '/'), ('sim', '/sim/'), ('/sim/', '/sim/'), (' /a/b ', '/a/b/'),
])
def test_normalize_namespace(namespace, expected):
    assert normalize_namespace(namespace) == expected


@pytest.mark.parametrize('namespace', [None, 3, ['/']])
def test_normalize_namespace_rejects_non_strings(namespace):
    with pytest.raises(ValueError, match='namespace'):
        normalize_namespace(namespace)
