#!/usr/bin/env python3
"""The rules of docs/architecture.md that a program can check, checked on the tree and the build.

    check_architecture.py SOURCE_DIR MODULE_GRAPH

MODULE_GRAPH is the file tests/CMakeLists.txt writes at configure time: one line per target,
"<target>: <the frugal targets it links>", read from the targets' LINK_LIBRARIES. The checks:

1. The link graph: no library module (frugal_<module>, or the library frugal_frugal) links the
   research tree (frugal_research), and cull links no backend (gl, software).
2. Includes: every `#include "<folder>/..."` of a library module names itself or a module its target
   links, directly or through others, so that the graph checked above is the graph the code has.
3. The command line (src/app/, src/batch/, research/commands/) includes no internal header: only
   the public <frugal/...>, app/, batch/, commands/, the research tree (lab/) and base/Format.h.
   The research tree (research/lab/) includes only <frugal/...>, lab/ and renderer/Research.h.
4. No function of the command line is longer than 80 lines (from its signature to its closing brace).
5. docs/architecture.md's module table: one row per folder of src/ and of research/, no other, each
   with the modules its files include directly ("depends on").

Prints one line per problem and exits 1 when there is any; `--self-test` checks the checker on
planted faults instead.
"""
import os
import re
import sys

MAX_FUNCTION_LINES = 80
SOURCE_SUFFIXES = ('.h', '.cpp', '.inl')
COMMAND_LINE = ('src/app', 'src/batch', 'research/commands')
COMMAND_LINE_MAY_INCLUDE = ('app/', 'batch/', 'commands/', 'lab/', 'base/Format.h')
RESEARCH_MAY_INCLUDE = ('lab/', 'renderer/Research.h')
BACKENDS = ('gl', 'software')
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def sources(folder):
    for root, _, names in os.walk(folder):
        for name in sorted(names):
            if name.endswith(SOURCE_SUFFIXES):
                yield os.path.join(root, name)


def includes(path):
    with open(path, encoding='utf-8') as f:
        return INCLUDE.findall(f.read())


def blank_literals(text):
    """`text` with comments, string and character literals blanked, newlines kept (so that braces
    inside them do not count and line numbers stay)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == '_')):
            k = text.find('(', i + 2)
            end = text.find(')' + text[i + 2:k] + '"', k)
            j = n if end < 0 else end + len(text[i + 2:k]) + 2
        elif c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum())):
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == '\\' else 1
            j = min(j + 1, n)
        else:
            out.append(c)
            i += 1
            continue
        out.append(re.sub(r'[^\n]', ' ', text[i:j]))
        i = j
    return ''.join(out)


def function_lengths(text):
    """(line, length) of every function body at namespace or class scope: a brace whose head (the
    text since the last ; { or }) ends in a parameter list, with what may follow one."""
    s = blank_literals(text)
    stack, last = [], 0
    for i, c in enumerate(s):
        if c not in ';{}':
            continue
        head = s[last:i]
        if c == '{':
            h = head.strip()
            parent = stack[-1][0] if stack else 'namespace'
            if re.search(r'\bnamespace\b', h) or h.startswith('extern'):
                kind = 'namespace'
            elif re.search(r'\b(class|struct|union|enum)\b', h) and '(' not in h:
                kind = 'type'
            elif parent in ('namespace', 'type') and ')' in h and not h.endswith('=') \
                    and re.search(r'\)[\w\s:&<>,*\->\[\]()]*$', h):
                kind = 'function'
            else:
                kind = 'block'
            stack.append((kind, i - len(head) + (len(head) - len(head.lstrip()))))
        elif c == '}' and stack:
            kind, start = stack.pop()
            if kind == 'function':
                first = s.count('\n', 0, start) + 1
                yield first, s.count('\n', 0, i) + 1 - first + 1
        last = i + 1


def read_graph(path):
    graph = {}
    with open(path, encoding='utf-8') as f:
        for line in f:
            if ':' in line:
                target, linked = line.split(':', 1)
                graph[target.strip()] = set(linked.split())
    return graph


def reachable(graph, start):
    seen, todo = set(), [start]
    while todo:
        for to in graph.get(todo.pop(), ()):
            if to not in seen:
                seen.add(to)
                todo.append(to)
    return seen


def module_folders(root):
    """{short name: folder} for every folder of src/ and research/ holding sources."""
    folders = {}
    for tree in ('src', 'research'):
        for name in sorted(os.listdir(os.path.join(root, tree))):
            folder = os.path.join(tree, name)
            if os.path.isdir(os.path.join(root, folder)) and any(sources(os.path.join(root, folder))):
                folders[name] = folder
    return folders


def direct_includes(root, folder, names):
    used = set()
    for path in sources(os.path.join(root, folder)):
        for included in includes(path):
            head = included.split('/')[0]
            if '/' in included and head in names:
                used.add(head)
    used.discard(os.path.basename(folder))
    return used


def doc_table(path):
    """{folder: (line, [depends on])} from the table under '## Modules'."""
    rows, in_section = {}, False
    with open(path, encoding='utf-8') as f:
        for number, line in enumerate(f, 1):
            if line.startswith('## '):
                in_section = line.strip() == '## Modules'
            if not in_section:
                continue
            m = re.match(r'^\|\s*`([^`]+)/`\s*\|.*\|\s*([^|]*?)\s*\|\s*$', line)
            if m:
                deps = m.group(2)
                rows[m.group(1)] = (number, [] if deps in ('—', '-', '') else [d.strip() for d in deps.split(',')])
    return rows


def check(root, graph_path):
    problems = []
    graph = read_graph(graph_path)
    folders = module_folders(root)
    # The library's modules and the library itself: every target of the graph but the research tree and
    # the command line.
    library = [t for t in graph if t not in ('frugal_research', 'frugal_app')]

    # 1. The link graph.
    for target in library:
        if 'frugal_research' in reachable(graph, target):
            problems.append(f'module graph: {target} links the research tree (frugal_research)')
    for backend in BACKENDS:
        if 'frugal_' + backend in reachable(graph, 'frugal_cull'):
            problems.append(f'module graph: cull links the backend {backend}')

    # 2. Includes follow the links.
    for name, folder in folders.items():
        target = 'frugal_' + name
        if target not in library:
            continue
        linked = {t[len('frugal_'):] for t in reachable(graph, target)}
        for other in sorted(direct_includes(root, folder, folders)):
            if other not in linked:
                problems.append(f'{folder}: includes {other}/ but {target} does not link frugal_{other}')

    # 3. What the command line and the research tree include.
    for folder, allowed in [(f, COMMAND_LINE_MAY_INCLUDE) for f in COMMAND_LINE] + \
                           [('research/lab', RESEARCH_MAY_INCLUDE)]:
        for path in sources(os.path.join(root, folder)):
            for included in includes(path):
                if not included.startswith(allowed):
                    problems.append(f'{os.path.relpath(path, root)}: includes "{included}", an internal header '
                                    f'({folder} may include <frugal/...> and {", ".join(allowed)})')

    # 4. Function lengths in the command line.
    for folder in COMMAND_LINE:
        for path in sources(os.path.join(root, folder)):
            with open(path, encoding='utf-8') as f:
                text = f.read()
            for line, length in function_lengths(text):
                if length > MAX_FUNCTION_LINES:
                    problems.append(f'{os.path.relpath(path, root)}:{line}: a function of {length} lines '
                                    f'(the command line keeps each within {MAX_FUNCTION_LINES})')

    # 5. The module table.
    doc = os.path.join(root, 'docs', 'architecture.md')
    rows = doc_table(doc)
    for name, folder in folders.items():
        if folder not in rows:
            problems.append(f'docs/architecture.md: the module table has no row for {folder}/')
            continue
        line, listed = rows[folder]
        actual = sorted(direct_includes(root, folder, folders))
        if listed != actual:
            problems.append(f'docs/architecture.md:{line}: {folder}/ depends on {", ".join(actual) or "—"} '
                            f'(its includes), the table says {", ".join(listed) or "—"}')
    for folder, (line, _) in rows.items():
        if folder not in folders.values():
            problems.append(f'docs/architecture.md:{line}: the module table names {folder}/, which is not a '
                            f'folder of sources')
    return problems


def self_test():
    """The checker finds planted faults (a checker that cannot fail checks nothing)."""
    long_function = 'int f(int a) {\n' + '    a += 1;\n' * 90 + '    return a;\n}\n'
    assert [n for _, n in function_lengths(long_function)] == [93], list(function_lengths(long_function))
    nested = ('namespace x {\nstruct S {\n    int g() const {\n' + '        return 1;\n' * 3 + '    }\n};\n'
              'const char* h() {\n    return R"(a { b } {{ )" "}";\n}\n}  // namespace x\n')
    assert [n for _, n in function_lengths(nested)] == [5, 3], list(function_lengths(nested))
    lambdas = 'void k() {\n    auto l = [](int) { return 0; };\n    if (true) {\n    }\n}\n'
    assert [n for _, n in function_lengths(lambdas)] == [5], list(function_lengths(lambdas))
    graph = {'frugal_cull': {'frugal_pipeline', 'frugal_raster'}, 'frugal_raster': {'frugal_software'},
             'frugal_software': {'frugal_research'}}
    assert 'frugal_software' in reachable(graph, 'frugal_cull')
    assert 'frugal_research' in reachable(graph, 'frugal_cull')
    print('self-test passed')


def main(argv):
    if argv[1:] == ['--self-test']:
        self_test()
        return 0
    if len(argv) != 3:
        print('usage: check_architecture.py SOURCE_DIR MODULE_GRAPH | --self-test', file=sys.stderr)
        return 2
    problems = check(argv[1], argv[2])
    for problem in problems:
        print('error: ' + problem)
    if not problems:
        print('architecture: the module graph, the includes, the command line and docs/architecture.md agree')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
