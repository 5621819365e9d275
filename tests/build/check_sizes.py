#!/usr/bin/env python3
"""Checks that no source file under the given tree is longer than MAX_FILE
lines and no function longer than MAX_FUNCTION lines (issue 19: files a
reader can hold in mind). A function is a top-level brace block whose
opening brace stands at column 0 (the project's style, which clang-format
keeps); its length counts from the line that names it to its closing brace.
C++ member functions defined in a class body are found the same way one
indentation level in. Generated code (lcm-gen output) lives in the build
tree, so is never looked at.

usage: check_sizes.py [--max-file N] [--max-function N] DIR...
Prints every breach and exits 1 if there is one."""
import argparse
import os
import re
import sys

SOURCE_SUFFIXES = ('.c', '.h', '.cpp', '.hpp')


def strip_comments_and_strings(text):
    """Blank out comments and string/char literals, keeping newlines, so
    braces inside them do not count."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:j]))
            i = j
        elif text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
            out.append(' ' * (j - i))
            i = j
        elif c in '"\'':
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            j = min(j + 1, n)
            out.append(c + re.sub(r'[^\n]', ' ', text[i + 1:j - 1]) + c)
            i = j
        else:
            out.append(c)
            i += 1
    return ''.join(out)


def functions(lines):
    """Yields (name, first_line, last_line), 1-based, for every function
    body opened by a brace alone at the start of a line (column 0 or one
    indentation level for C++ in-class definitions)."""
    i = 0
    while i < len(lines):
        m = re.match(r'^( {0,4})\{\s*$', lines[i])
        if not m:
            i += 1
            continue
        indent = m.group(1)
        # The signature: the non-blank lines above, back to one that ends
        # a previous statement or block.
        start = i
        while start > 0:
            above = lines[start - 1].rstrip()
            if not above or above.endswith((';', '}', '{')) or above.startswith('#'):
                break
            start -= 1
        signature = ' '.join(l.strip() for l in lines[start:i])
        name = re.search(r'([A-Za-z_][\w:~]*)\s*\(', signature)
        depth = 0
        j = i
        while j < len(lines):
            depth += lines[j].count('{') - lines[j].count('}')
            if depth == 0:
                break
            j += 1
        if name and j < len(lines) and lines[j].startswith(indent + '}'):
            yield name.group(1), start + 1, j + 1
        i = j + 1


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--max-file', type=int, default=600)
    parser.add_argument('--max-function', type=int, default=100)
    parser.add_argument('dirs', nargs='+')
    args = parser.parse_args()
    breaches = 0
    checked = 0
    for top in args.dirs:
        for root, _, names in os.walk(top):
            for name in sorted(names):
                if not name.endswith(SOURCE_SUFFIXES):
                    continue
                path = os.path.join(root, name)
                with open(path, encoding='utf-8') as f:
                    text = f.read()
                checked += 1
                lines = strip_comments_and_strings(text).split('\n')
                if text.endswith('\n'):
                    lines.pop()
                if len(lines) > args.max_file:
                    print(f'{path}: {len(lines)} lines (at most {args.max_file})')
                    breaches += 1
                for fn, first, last in functions(lines):
                    length = last - first + 1
                    if length > args.max_function:
                        print(f'{path}:{first}: {fn} is {length} lines '
                              f'(at most {args.max_function})')
                        breaches += 1
    print(f'{checked} files checked, {breaches} over the limits')
    return 1 if breaches else 0


if __name__ == '__main__':
    sys.exit(main())
