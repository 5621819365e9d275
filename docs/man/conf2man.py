#!/usr/bin/env python3
"""rtedged.conf(5) from the daemon's key table.

    conf2man.py KEYS_JSON TEMPLATE OUTPUT VERSION SYSCONFDIR

KEYS_JSON is what `rtedged --help-config=json` prints; TEMPLATE the page's
hand-written frame (rtedged.conf.5.in), in which @KEYS@ becomes one .SS per
section and one .TP per key (name, help, type, range and unit, default,
runtime or fixed), and @VERSION@ and @SYSCONFDIR@ are replaced.
"""
import json
import re
import sys


def roff_text(text):
    """text as roff input: escapes, `code` in bold, non-ASCII as \\[uXXXX]."""
    out = text.replace('\\', '\\e').replace('-', '\\-')
    out = re.sub(r'`([^`]*)`', r'\\fB\1\\fR', out)
    out = ''.join(c if ord(c) < 128 else '\\[u%04X]' % ord(c) for c in out)
    # a line must not start with a control character
    return '\n'.join('\\&' + line if line[:1] in ('.', "'") else line
                     for line in out.split('\n'))


def number(value, kind):
    return str(int(value)) if kind == 'int' else '%g' % value


def value_line(k):
    """Type, range or choices, unit, the default and runtime, as one sentence."""
    kind = k['type']
    unit = (' ' + k['unit']) if k['unit'] else ''
    if kind in ('int', 'real'):
        what = '%s %s to %s%s' % ('Integer' if kind == 'int' else 'Number',
                                   number(k['min'], kind), number(k['max'], kind), unit)
        if 'unset' in k:
            what += ', or %s' % number(k['unset'], kind)
    elif kind == 'bool':
        what = '`true` or `false`'
    elif kind == 'choice':
        what = 'One of ' + ', '.join('`%s`' % c for c in k['choices'])
    else:
        what = 'Text of at most %d characters' % k['max_length']
    default = '`%s`' % k['default'] if k['default'] else 'empty'
    when = 'runtime' if k['runtime'] else 'fixed at start'
    return '%s; default %s; %s.' % (what, default, when)


def keys_roff(keys):
    lines, section = [], None
    for k in keys:
        if k['section'] != section:
            section = k['section']
            lines.append('.SS "[%s]"' % section)
        lines += ['.TP', '.B %s' % roff_text(k['key']),
                  roff_text(k['help'].replace('\n', ' ')), '.br',
                  roff_text(value_line(k))]
    return '\n'.join(lines)


def main():
    keys_json, template, output, version, sysconfdir = sys.argv[1:6]
    with open(keys_json, encoding='utf-8') as f:
        keys = json.load(f)['keys']
    if not keys:
        sys.exit('conf2man.py: no keys in ' + keys_json)
    with open(template, encoding='utf-8') as f:
        page = f.read()
    page = (page.replace('@KEYS@', keys_roff(keys)).replace('@VERSION@', version)
            .replace('@SYSCONFDIR@', sysconfdir))
    with open(output, 'w', encoding='utf-8') as f:
        f.write(page)


if __name__ == '__main__':
    main()
