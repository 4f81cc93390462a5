#!/usr/bin/env python3
"""The architecture as a test (docs/development.md, "Layout").

Reads the allowed arrows between modules from the top CMakeLists.txt (the
`set(SHADOWCERT_ALLOWED_<module> ...)` lines, the one statement of them) and checks every
`#include` of the tree against them:
  1. a file of module M includes project headers only from M and from the modules M may use;
  2. a header under M/detail/ is included only by M's own files and by tests/M/;
  3. every project header that is included exists (no stale path after a move);
  4. CGAL is included only from .cpp files of io/, exact/ and reference/ (a TU with CGAL costs
     about 10 s to compile, so no header may carry it), OpenMesh only from .cpp files of
     contour/, and GL only from gpu/.
Prints one line per violation (file:line: what) and exits 1 if there is any.
Usage: layering_test.py SOURCE_DIR
"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
ALLOWED = re.compile(r'^set\(SHADOWCERT_ALLOWED_(\w+)((?:\s+\w+)*)\s*\)', re.M)
CGAL_MODULES = {"io", "exact", "reference"}
GL_HEADERS = ("epoxy/", "EGL/", "GL/", "glm/")
SOURCE_SUFFIXES = {".h", ".cpp"}
OTHER_FOLDERS = ("tests", "bench", "fuzz")  # may include any module's interface


def main(root: pathlib.Path) -> int:
    allowed = {m: set(deps.split()) for m, deps in ALLOWED.findall((root / "CMakeLists.txt").read_text())}
    if not allowed:
        print(f"{root / 'CMakeLists.txt'}: no set(SHADOWCERT_ALLOWED_...) lines")
        return 1
    problems = []
    for path in sorted(root.rglob("*")):
        rel = path.relative_to(root)
        if path.suffix not in SOURCE_SUFFIXES or rel.parts[0] not in set(allowed) | set(OTHER_FOLDERS):
            continue
        owner = rel.parts[0]
        tested = rel.parts[1] if owner == "tests" and len(rel.parts) > 2 else None
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            match = INCLUDE.match(line)
            if not match:
                continue
            quote, target = match.groups()
            where = f"{rel}:{number}"
            if quote == "<":
                if target.startswith("CGAL/") and (owner not in CGAL_MODULES or path.suffix != ".cpp"):
                    problems.append(f"{where}: <{target}> outside the .cpp files of {sorted(CGAL_MODULES)}")
                if target.startswith("OpenMesh/") and (owner != "contour" or path.suffix != ".cpp"):
                    problems.append(f"{where}: <{target}> outside the .cpp files of contour/")
                if target.startswith(GL_HEADERS) and owner not in ("gpu", "tests", "bench"):
                    problems.append(f"{where}: <{target}> outside gpu/")
                continue
            module = target.split("/", 1)[0]
            if module not in allowed:
                continue  # a header beside the including file (tests' helpers, generated files)
            if not (root / target).is_file() and target != "gpu/embedded_shaders.h":
                problems.append(f'{where}: "{target}" does not exist')
            if owner in allowed and module != owner and module not in allowed[owner]:
                problems.append(f'{where}: {owner} may not use {module} ("{target}"); '
                                f"allowed: {sorted(allowed[owner]) or 'nothing'}")
            if "/detail/" in target and module != owner and module != tested:
                problems.append(f'{where}: "{target}" is private to {module}/')
    for problem in problems:
        print(problem)
    print(f"layering: {len(problems)} violation(s) of the arrows {allowed}")
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(pathlib.Path(sys.argv[1])))
