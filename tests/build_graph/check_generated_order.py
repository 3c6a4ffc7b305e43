#!/usr/bin/env python3
"""Build-order check of a Ninja build tree (after a build):

1. Every compile that read a generated file at the last build (its header deps, `ninja -t deps`,
   that some build edge produces: fastddsgen's robodds.h, the field visitors' robodds_visit.hpp,
   idlc's headers, ...) reaches the edge generating it through its inputs (explicit, implicit or
   order-only, transitively). Otherwise a fresh build of that target alone, or a lucky -j order,
   compiles before the header is written.
2. fastddsgen runs with -t inside the build tree: by default it preprocesses into
   /tmp/<idl name>.cc, one file for every build on the machine (cmake/IdlGenerate.cmake).

Usage: check_generated_order.py BUILD_DIR [NINJA]. Exit 0 if both hold, 1 naming each fault."""
import os
import re
import subprocess
import sys

COMPILE_RULE = re.compile(r'^C(XX)?_COMPILER__')


def logical_lines(path):
    """The lines of a .ninja file with $-newline continuations joined."""
    pending = ''
    with open(path) as f:
        for line in f:
            line = line.rstrip('\n')
            trailing = len(line) - len(line.rstrip('$'))
            if trailing % 2 == 1:  # an unescaped $ at the end continues the line
                pending += line[:-1]
                continue
            yield pending + line
            pending = ''


def unescape_paths(text, workdir):
    """Space-separated ninja paths ('$ ', '$:', '$$' escapes; ${cmake_ninja_workdir})."""
    paths, current, i = [], '', 0
    while i < len(text):
        c = text[i]
        if c == '$' and i + 1 < len(text):
            n = text[i + 1]
            if n in ' :$':
                current += n
                i += 2
                continue
            if n == '{':
                end = text.index('}', i)
                name = text[i + 2:end]
                current += workdir if name == 'cmake_ninja_workdir' else '${%s}' % name
                i = end + 1
                continue
        if c == ' ':
            if current:
                paths.append(current)
            current = ''
        else:
            current += c
        i += 1
    if current:
        paths.append(current)
    return paths


class Graph:
    def __init__(self, build_dir):
        self.build_dir = os.path.abspath(build_dir)
        self.edges = []  # (outputs, rule, inputs, variables)
        self.producer = {}
        self._parse(os.path.join(self.build_dir, 'build.ninja'))

    def norm(self, path):
        prefix = self.build_dir + '/'
        return path[len(prefix):] if path.startswith(prefix) else path

    def _parse(self, path):
        edge = None
        for line in logical_lines(path):
            if edge is not None and line.startswith('  ') and '=' in line:
                key, value = line.strip().split('=', 1)
                edge[3][key.strip()] = value.strip()
                continue
            edge = None
            if line.startswith(('include ', 'subninja ')):
                self._parse(os.path.join(self.build_dir, line.split(None, 1)[1].strip()))
            elif line.startswith('build '):
                body = line[len('build '):]
                colon = re.search(r'(?<!\$):', body).start()
                outputs = [self.norm(p) for p in unescape_paths(body[:colon], self.build_dir + '/') if p != '|']
                rest = unescape_paths(body[colon + 1:], self.build_dir + '/')
                inputs = [self.norm(p) for p in rest[1:] if p not in ('|', '||', '|@')]
                edge = (outputs, rest[0], inputs, {})
                for out in outputs:
                    self.producer.setdefault(out, len(self.edges))
                self.edges.append(edge)

    def reachable(self, node):
        """Every node the edge producing `node` waits for, transitively."""
        seen, stack = set(), [node]
        while stack:
            n = stack.pop()
            if n not in seen:
                seen.add(n)
                index = self.producer.get(n)
                if index is not None:
                    stack.extend(self.edges[index][2])
        return seen


def recorded_deps(build_dir, ninja, graph):
    # -n: read the logs only (a ninja building in this tree at the same time keeps them to itself).
    out = subprocess.run([ninja, '-n', '-C', build_dir, '-t', 'deps'], check=True, capture_output=True, text=True).stdout
    deps, current = {}, None
    for line in out.splitlines():
        if line and not line[0].isspace():
            current = deps.setdefault(line.split(':', 1)[0], [])
        elif line.strip() and current is not None:
            current.append(graph.norm(line.strip()))
    return deps


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    build_dir = sys.argv[1]
    ninja = sys.argv[2] if len(sys.argv) == 3 else 'ninja'
    graph = Graph(build_dir)
    deps = recorded_deps(build_dir, ninja, graph)
    faults, readers = [], 0
    for outputs, rule, _, _ in graph.edges:
        if not COMPILE_RULE.match(rule):
            continue
        generated = [d for d in deps.get(outputs[0], []) if d in graph.producer]
        if not generated:
            continue
        readers += 1
        waits_for = graph.reachable(outputs[0])
        faults += [f'{outputs[0]} reads {g} but does not wait for the command generating it'
                   for g in generated if g not in waits_for]
    if readers == 0:
        faults.append('no compile read a generated header at the last build (nothing recorded: build first)')
    generators = 0
    for outputs, rule, _, variables in graph.edges:
        command = variables.get('COMMAND', '')
        for args in re.findall(r'fastddsgen[^\s/]*\s+([^&;]*)', command):
            generators += 1
            temp = re.search(r'(?:^|\s)-t\s+(\S+)', args)
            if not temp or not os.path.abspath(temp.group(1)).startswith(graph.build_dir + '/'):
                faults.append(f'fastddsgen for {outputs[0]} has no -t inside {graph.build_dir} (default /tmp is shared '
                              f'by every build on the machine): {args.strip()}')
    if generators == 0:
        faults.append('no fastddsgen command found in build.ninja')
    for fault in faults:
        print('FAIL:', fault)
    print(f'{readers} compiles read generated headers, {generators} fastddsgen command(s): '
          f'{"ok" if not faults else str(len(faults)) + " fault(s)"}')
    return 1 if faults else 0


if __name__ == '__main__':
    sys.exit(main())
