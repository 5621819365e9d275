#!/usr/bin/python3
"""The man pages (docs/man): each renders without a warning (man-db's man
and groff), and none is stale against the programs:

- rtedge.1: every command of `rtedge --help` has its subsection, and every
  option of each `rtedge COMMAND --help` is in the page;
- rtedged.8: every option of `rtedged --help` is under OPTIONS, every
  channel key's default name under LCM CHANNELS;
- rtedged.conf.5: every key of `rtedged --help-config` is under its
  section's heading with its default, and the page's example is a
  configuration rtedged accepts;
- the tools' pages (rtedge-subscribe.1, rtedge-render-log.1, rtedge-web.1,
  rtedge-spy.1): every option of the tool's --help, and every choice of
  an option, is under OPTIONS; every environment variable its source reads
  is under ENVIRONMENT; SEE ALSO names rtedged(8), rtedge(1) and each other
  tool. A tool that cannot start for want of a Python module (aiohttp,
  cv2) is noted and its options are not checked.

It also checks `rtedged --help-config=json`, which the page is made from,
against `--help-config`: the same keys in the same order with the same
help, type, range, default and runtime mark.

    check_man.py RTEDGE RTEDGED|'' [--tool PAGE=PROGRAM]... PAGE...

(--tool rtedge-web.1=src/web/rtedge-web: the page's program, Python run
with /usr/bin/python3, or a shell script.) In a cross build meson test sets
MESON_EXE_WRAPPER (qemu-user): rtedge and rtedged run through it, the
tools (scripts) do not.
"""
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

failures = []


def fail(msg):
    failures.append(msg)
    print('FAIL: ' + msg)


def run(*args):
    args = shlex.split(os.environ.get('MESON_EXE_WRAPPER', '')) + list(args)
    return subprocess.run(args, capture_output=True, text=True, check=True).stdout


def render_warnings(page):
    """groff's and man's warnings for the page (empty when there is none)."""
    env = dict(os.environ, LC_ALL='C.UTF-8', MANWIDTH='80')
    out = []
    groff = subprocess.run(['groff', '-man', '-k', '-t', '-ww', '-z', page], env=env,
                           capture_output=True, text=True)
    out += [groff.stderr.strip()] if groff.stderr.strip() or groff.returncode else []
    if shutil.which('man'):
        man = subprocess.run(['man', '--warnings=w', '-E', 'UTF-8', '-l', page], env=env,
                             capture_output=True, text=True)
        out += [man.stderr.strip()] if man.stderr.strip() or man.returncode else []
    return out


def rendered(page):
    """The page as plain text, wide enough that no line of it is broken."""
    return subprocess.run(['groff', '-man', '-k', '-t', '-Tascii', '-P-cbou', '-rLL=400n',
                           page], capture_output=True, text=True, check=True).stdout


def sections(text):
    """{heading: text} of a rendered page's sections (headings at column 0)."""
    out, name = {}, None
    for line in text.splitlines():
        if re.match(r'[A-Z][A-Z ]+$', line):
            name = line.strip()
            out[name] = ''
        elif name:
            out[name] += line + '\n'
    return out


def has_word(text, word):
    return re.search(r'(?<![\w-])' + re.escape(word) + r'(?![\w-])', text) is not None


def check_rtedge(page, rtedge):
    text = rendered(page)
    source = open(page, encoding='utf-8').read()
    headings = ' '.join(re.findall(r'^\.SS "?([^"\n]*)', source, re.M))
    commands = [line.split()[0] for line in run(rtedge, '--help').split('commands:\n')[1]
                .splitlines() if line.strip()]
    for cmd in commands:
        if not has_word(headings.replace(',', ' '), cmd):
            fail('rtedge.1: no subsection for the command %s' % cmd)
        for opt in re.findall(r'^  (--[\w-]+)', run(rtedge, cmd, '--help'), re.M):
            where = 'OPTIONS' if opt == '--help' else 'COMMANDS'
            if not has_word(sections(text).get(where, ''), opt):
                fail('rtedge.1: rtedge %s %s is not described' % (cmd, opt))
    return len(commands)


def check_rtedged(page, rtedged, keys):
    parts = sections(rendered(page))
    options = re.findall(r'^  (-[\w=-]+)', run(rtedged, '--help'), re.M)
    for opt in options:
        if not has_word(parts.get('OPTIONS', ''), opt):
            fail('rtedged.8: the option %s is not under OPTIONS' % opt)
    channels = [k for k in keys if k['key'].endswith('channel') and k['default']]
    for k in channels:
        name = '%s.%s' % (k['section'], k['key'])
        block = parts.get('LCM CHANNELS', '')
        if not has_word(block, k['default']) or not has_word(block, name):
            fail('rtedged.8: the channel %s (%s) is not under LCM CHANNELS' % (k['default'], name))
    return len(options), len(channels)


def tool_help(program):
    """The tool's --help, or None when it lacks a Python module (noted)."""
    with open(program, encoding='utf-8') as f:
        python = 'python' in f.readline()
    args = (['/usr/bin/python3'] if python else []) + [program, '--help']
    env = dict(os.environ, COLUMNS='1000', LC_ALL='C.UTF-8')
    r = subprocess.run(args, capture_output=True, text=True, env=env)
    missing = re.search(r"ModuleNotFoundError: No module named '([\w.]+)'", r.stderr)
    if r.returncode and missing:
        print('note: %s cannot start without the Python module %s: its options are not '
              'checked' % (os.path.basename(program), missing.group(1)))
        return None
    if r.returncode:
        fail('%s --help exits %d: %s' % (program, r.returncode, r.stderr.strip()))
        return None
    return r.stdout


def environment_variables(program):
    """The variables the tool's source reads (os.environ in Python, ${X} in sh)."""
    source = open(program, encoding='utf-8').read()
    found = re.findall(r'os\.environ(?:\.get\(|\[)\s*["\']([A-Z][A-Z0-9_]*)', source)
    found += re.findall(r'\$\{([A-Z][A-Z0-9_]*)', source)
    return sorted(set(found))


def check_tool(page, program, tools):
    name = os.path.basename(page)
    parts = sections(rendered(page))
    options = parts.get('OPTIONS', '')
    text = tool_help(program)
    checked = []
    if text is not None:
        opts = sorted(set(re.findall(r'(?<![\w-])(--[a-z][\w-]*|-[a-zA-Z](?![\w-]))', text)))
        for opt in opts:
            if not has_word(options, opt):
                fail('%s: the option %s of %s --help is not under OPTIONS' % (name, opt, program))
        choices = [c for group in re.findall(r'\{([\w,-]+)\}', text) for c in group.split(',')]
        for choice in sorted(set(choices)):
            if not has_word(options, choice):
                fail('%s: the choice %s of %s --help is not under OPTIONS'
                     % (name, choice, program))
        checked.append('%d options, %d choices' % (len(opts), len(set(choices))))
    variables = environment_variables(program)
    for var in variables:
        if not has_word(parts.get('ENVIRONMENT', ''), var):
            fail('%s: %s reads %s: it is not under ENVIRONMENT' % (name, program, var))
    checked.append('environment: ' + (' '.join(variables) or 'none'))
    see_also = ' '.join(parts.get('SEE ALSO', '').split())
    for other in ['rtedged(8)', 'rtedge(1)'] + ['%s(1)' % os.path.splitext(t)[0]
                                               for t in tools if t != name]:
        if other not in see_also:
            fail('%s: SEE ALSO does not name %s' % (name, other))
    return ', '.join(checked)


def help_config_keys(text):
    """[(section, key, comment lines, value)] of `rtedged --help-config`."""
    out, section, comments = [], None, []
    for line in text.splitlines():
        if line.startswith('['):
            section, comments = line.strip('[]'), []
        elif line.startswith('# '):
            comments.append(line[2:])
        elif section and ' = ' in line:
            key, value = line.split(' = ', 1)
            out.append((section, key, comments, value))
            comments = []
        elif not line:
            comments = []
    return out


def type_line(k):
    """The type line --help-config writes for the JSON key k."""
    number = (lambda v: '%d' % v) if k['type'] == 'int' else (lambda v: '%g' % v)
    what = {'int': lambda: 'integer %d..%d' % (k['min'], k['max']),
            'real': lambda: 'number %s..%s' % (number(k['min']), number(k['max'])),
            'bool': lambda: 'true or false',
            'text': lambda: 'text, at most %d characters' % k['max_length'],
            'choice': lambda: 'one of ' + ' '.join(k['choices'])}[k['type']]()
    if 'unset' in k:
        what += ', or ' + number(k['unset'])
    return '%s; default %s%s' % (what, k['default'] or '(empty)',
                                 ' (runtime)' if k['runtime'] else '')


def check_json(keys, text_keys):
    if [(k['section'], k['key']) for k in keys] != [(s, k) for s, k, _, _ in text_keys]:
        fail('--help-config=json and --help-config list different keys')
        return
    for k, (_, _, comments, value) in zip(keys, text_keys):
        name = '%s.%s' % (k['section'], k['key'])
        if comments != k['help'].split('\n') + [type_line(k)]:
            fail('--help-config=json: %s: %r and %r differ from --help-config: %r'
                 % (name, k['help'], type_line(k), comments))
        # the units the names say
        for suffix, unit in (('ms', 'ms'), ('_px', 'px')):
            if (k['key'] == suffix or k['key'].endswith('_' + suffix.lstrip('_'))) and \
                    k['unit'] != unit:
                fail('--help-config=json: %s has the unit %r, not %s' % (name, k['unit'], unit))


def check_conf(page, rtedged, text_keys):
    parts = sections(rendered(page))
    headings = {}
    current = None
    for line in parts.get('KEYS', '').splitlines():
        m = re.match(r'   \[(\w+)\]$', line)
        if m:
            current = headings.setdefault(m.group(1), [])
        elif current is not None:
            current.append(line)
    for section, key, comments, _ in text_keys:
        block = '\n'.join(headings.get(section, []))
        m = re.search(r'^       %s(?:\n| +)(.*?)(?=^       \S|\Z)' % re.escape(key),
                      block, re.M | re.S)
        default = re.search(r'; default (.*?)(?: \(runtime\))?$', comments[-1]).group(1)
        default = 'empty' if default == '(empty)' else default
        if not m:
            fail('rtedged.conf.5: no %s under [%s]' % (key, section))
        elif not re.search(r'; default %s;' % re.escape(default), ' '.join(m.group(1).split())):
            fail('rtedged.conf.5: %s.%s: no "default %s" in %r' % (section, key, default,
                                                                    m.group(1)))
    example = re.search(r'^\.EX\n(.*?)^\.EE', open(page, encoding='utf-8').read(), re.M | re.S)
    with tempfile.NamedTemporaryFile('w', suffix='.conf') as f:
        f.write(example.group(1).replace('\\e', '\\').replace('\\-', '-') if example else '')
        f.flush()
        check = subprocess.run(shlex.split(os.environ.get('MESON_EXE_WRAPPER', '')) +
                               [rtedged, '--config', f.name, '--check-config'],
                               capture_output=True, text=True)
        if not example or check.returncode:
            fail('rtedged.conf.5: the example is not a good configuration: ' +
                 check.stderr.strip())
    return len(text_keys)


def main():
    rtedge, rtedged, rest = sys.argv[1], sys.argv[2], sys.argv[3:]
    tools, pages = {}, []
    while rest:
        if rest[0] == '--tool':
            page, program = rest[1].split('=', 1)
            tools[page] = program
            rest = rest[2:]
        else:
            pages.append(rest.pop(0))
    if not shutil.which('groff'):
        print('SKIP: groff is not installed (Debian groff-base)')
        sys.exit(77)
    if not shutil.which('man'):
        print('note: man-db is not installed: the pages are checked with groff alone')
    keys = text_keys = None
    if rtedged:
        keys = json.loads(run(rtedged, '--help-config=json'))['keys']
        text_keys = help_config_keys(run(rtedged, '--help-config'))
        before = len(failures)
        check_json(keys, text_keys)
        if len(failures) == before:
            print('ok: --help-config=json: %d keys, as --help-config has them' % len(keys))
    for page in pages:
        name = os.path.basename(page)
        before = len(failures)
        for warning in render_warnings(page):
            fail('%s: rendering warns:\n%s' % (name, warning))
        if name == 'rtedge.1':
            what = '%d commands and their options' % check_rtedge(page, rtedge)
        elif name == 'rtedged.8':
            what = '%d options, %d channels' % check_rtedged(page, rtedged, keys)
        elif name == 'rtedged.conf.5':
            what = '%d keys, the example' % check_conf(page, rtedged, text_keys)
        elif name in tools:
            what = check_tool(page, tools[name], tools)
        else:
            what = fail('%s: no checks for this page' % name)
        if len(failures) == before:
            print('ok: %s renders without a warning; %s' % (name, what))
    if failures:
        sys.exit('%d failures' % len(failures))


if __name__ == '__main__':
    main()
