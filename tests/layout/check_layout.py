#!/usr/bin/python3
"""The source layout's rules, checked (Debian's /usr/bin/python3, standard library only):

  - an include in src/tsmframe/<floor>/ names the same or a lower floor; the floors, bottom to
    top, are util < linalg < element < model < contact < assembly < solver < io < study, and
    app/ and python/ above them may include anything (tsmframe/version.hpp counts as util);
  - no function in src/ is longer than 120 lines (measured by Universal Ctags; lambdas are part
    of the function around them, not functions of their own);
  - no .cpp in src/ is longer than 600 lines;
  - no import circle among the Python files of scripts/ and python/tsmframe/.

Each violation is one line, file:line: what. A short summary follows; the exit code is 1 on any
violation, 2 when the check cannot run (no Universal Ctags).

    /usr/bin/python3 tests/layout/check_layout.py [SOURCE_DIR]    (default: this checkout)
"""
import ast
import os
import re
import shutil
import subprocess
import sys

FLOORS = ["util", "linalg", "element", "model", "contact", "assembly", "solver", "io", "study"]
TOP = ["app", "python"]
FUNCTION_LIMIT = 120
CPP_LIMIT = 600
PYTHON_ROOTS = [("scripts", "scripts"), ("python", "python/tsmframe")]  # (import root, files)

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
CXX_SUFFIXES = (".hpp", ".cpp", ".h", ".hh", ".cc", ".inl")


def floor_of_path(relative):
    """The floor of a path below src/tsmframe/: its first folder; a file right in it is util."""
    parts = relative.split("/")
    return parts[0] if len(parts) > 1 else "util"


def source_files(root, top, suffixes):
    found = []
    for folder, dirs, files in os.walk(os.path.join(root, top)):
        dirs.sort()
        for name in sorted(files):
            if name.endswith(suffixes):
                found.append(os.path.relpath(os.path.join(folder, name), root))
    return found


def check_includes(root):
    """Violations of the floor order, and the count of tsmframe includes seen."""
    violations, seen = [], 0
    base = os.path.join(root, "src", "tsmframe")
    for path in source_files(root, "src/tsmframe", CXX_SUFFIXES):
        floor = floor_of_path(os.path.relpath(os.path.join(root, path), base))
        if floor not in FLOORS:
            violations.append(f"{path}:1: folder '{floor}' is not a floor (add it to FLOORS in its place)")
            continue
        with open(os.path.join(root, path), encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                match = INCLUDE.match(line)
                if not match:
                    continue
                bracket, name = match.groups()
                if name.startswith("tsmframe/"):
                    target = floor_of_path(name[len("tsmframe/"):])
                elif bracket == '"':  # relative to the including file
                    resolved = os.path.normpath(os.path.join(os.path.dirname(os.path.join(root, path)), name))
                    if not resolved.startswith(base + os.sep):
                        continue
                    target = floor_of_path(os.path.relpath(resolved, base))
                else:
                    continue
                seen += 1
                if target not in FLOORS:
                    violations.append(f"{path}:{number}: includes {name}: '{target}' is not a floor")
                elif FLOORS.index(target) > FLOORS.index(floor):
                    violations.append(f"{path}:{number}: includes {name}: {floor} may not include {target}, a higher floor")
    return violations, seen


def ctags_functions(root):
    """(file, first line, last line, name) of every function definition in src/, lambdas left out."""
    command = ["ctags", "--kinds-C++=f", "--fields=+ne", "-x", "-R",
               "--_xformat=%{input}\t%{line}\t%{end}\t%{scopeKind}\t%{scope}\t%N", "src"]
    done = subprocess.run(command, cwd=root, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError("ctags failed: " + done.stderr.strip().replace("\n", " "))
    functions = []
    for row in done.stdout.splitlines():
        path, first, last, scope_kind, scope, name = row.split("\t")
        if name.startswith("__anon"):  # a lambda
            continue
        if scope_kind in ("class", "struct", "union") and scope != "-":
            name = scope.split("::")[-1] + "::" + name
        end = int(last) if last.isdigit() else int(first)
        functions.append((path, int(first), end, name))
    return functions


def check_functions(functions):
    violations = []
    for path, first, last, name in sorted(functions):
        length = last - first + 1
        if length > FUNCTION_LIMIT:
            violations.append(f"{path}:{first}: function {name} is {length} lines (limit {FUNCTION_LIMIT})")
    return violations


def check_cpp_lengths(root):
    violations, longest = [], 0
    files = source_files(root, "src", (".cpp",))
    for path in files:
        with open(os.path.join(root, path), encoding="utf-8") as f:
            length = sum(1 for _ in f)
        longest = max(longest, length)
        if length > CPP_LIMIT:
            violations.append(f"{path}:1: {length} lines (limit {CPP_LIMIT})")
    return violations, len(files), longest


def python_modules(root):
    """Module name -> file, for the files of each import root (scripts/ runs from scripts/)."""
    modules = {}
    for import_root, folder in PYTHON_ROOTS:
        for path in source_files(root, folder, (".py",)):
            parts = os.path.relpath(os.path.join(root, path), os.path.join(root, import_root))[:-3].split(os.sep)
            if parts[-1] == "__init__":
                parts = parts[:-1]
            modules[".".join(parts)] = path
    return modules


def known(name, importer, modules):
    """The module of ours that an import of `name` runs: its longest prefix that is a module. A
    package the importer lies in is left out: its __init__ is already running (or has run)."""
    parts = name.split(".")
    for n in range(len(parts), 0, -1):
        candidate = ".".join(parts[:n])
        if candidate in modules:
            inside = importer == candidate or importer.startswith(candidate + ".")
            if n < len(parts) and inside and modules[candidate].endswith("__init__.py"):
                return None
            return candidate
    return None


def imports_of(module, path, modules, root):
    """(imported module, line) for every import of one of ours, at any depth of the file."""
    with open(os.path.join(root, path), encoding="utf-8") as f:
        tree = ast.parse(f.read(), filename=path)
    package = module if path.endswith("__init__.py") else module.rpartition(".")[0]
    edges = []
    for node in ast.walk(tree):
        names = []
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".") if package else []
                anchor = anchor[:len(anchor) - (node.level - 1)]
                base = ".".join(anchor + ([node.module] if node.module else []))
            # `from base import name` runs base.name when that is a module, else base
            names = [f"{base}.{alias.name}" if base else alias.name for alias in node.names]
            names = [n if n in modules else base for n in names]
        for name in names:
            target = known(name, module, modules) if name else None
            if target is not None:
                edges.append((target, node.lineno))
    return edges


def circles(graph):
    """Strongly connected components with a cycle (Tarjan), each as a list of modules."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1 or v in graph[v]:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def cycle_through(start, members, graph):
    """A shortest path start -> ... -> start inside one component."""
    paths, seen = [[start]], {start}
    while paths:
        following = []
        for path in paths:
            for w in sorted(graph[path[-1]]):
                if w == start:
                    return path + [start]
                if w in members and w not in seen:
                    seen.add(w)
                    following.append(path + [w])
        paths = following
    return [start, start]


def check_imports(root):
    modules = python_modules(root)
    graph, lines = {m: set() for m in modules}, {}
    for module, path in modules.items():
        for target, line in imports_of(module, path, modules, root):
            graph[module].add(target)
            lines.setdefault((module, target), line)
    violations = []
    for component in circles(graph):
        cycle = cycle_through(component[0], set(component), graph)
        first = modules[cycle[0]]
        violations.append(f"{first}:{lines[(cycle[0], cycle[1])]}: import circle: {' -> '.join(cycle)}")
    return violations, len(modules), sum(len(t) for t in graph.values())


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    if shutil.which("ctags") is None:
        print("check_layout: cannot measure functions: Universal Ctags is missing (apt-get install universal-ctags, or scripts/setup.sh)")
        return 2
    try:
        functions = ctags_functions(root)
    except (RuntimeError, ValueError) as e:
        print(f"check_layout: cannot measure functions: {e} (is ctags Universal Ctags? apt-get install universal-ctags)")
        return 2

    include_violations, include_count = check_includes(root)
    function_violations = check_functions(functions)
    cpp_violations, cpp_count, longest_cpp = check_cpp_lengths(root)
    import_violations, module_count, import_count = check_imports(root)
    violations = include_violations + function_violations + cpp_violations + import_violations
    for v in violations:
        print(v)

    longest_function = max((last - first + 1 for _, first, last, _ in functions), default=0)
    print(f"floors: {' < '.join(FLOORS)} < {', '.join(TOP)}")
    print(f"includes: {include_count} of tsmframe headers in src/tsmframe/, {len(include_violations)} against the floor order")
    print(f"functions: {len(functions)} in src/, longest {longest_function} lines, "
          f"{len(function_violations)} over {FUNCTION_LIMIT}")
    print(f".cpp files: {cpp_count} in src/, longest {longest_cpp} lines, {len(cpp_violations)} over {CPP_LIMIT}")
    print(f"python: {module_count} modules in scripts/ and python/tsmframe/, {import_count} imports among them, "
          f"{len(import_violations)} circles")
    print(f"layout: {'ok' if not violations else f'{len(violations)} violation' + ('s' if len(violations) > 1 else '')}")
    return 1 if violations else 0


if __name__ == "__main__":
    sys.exit(main())
