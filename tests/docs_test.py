#!/usr/bin/env python3
"""The docs' tables of modules and options against the code they describe.

    docs_test.py SHADOWCERT SOURCE_DIR

Checks, printing one line per mismatch (exit 1 on any):
  - modules: the arrows of the top CMakeLists.txt (SHADOWCERT_ALLOWED_<module>) against the
    README's module block and docs/development.md's layout table: every module listed in each,
    with the same "may use" set; every module folder has its CMakeLists.txt;
  - options: every subcommand of `shadowcert --help` has its section in docs/cli.md, and in that
    section every option of `shadowcert SUB --help` is documented, and every option the section's
    tables document exists in `--help`;
  - method names: the `--method` values that docs/cli.md's render heading lists are exactly those
    `shadowcert render --help` lists, and `diff --methods all` is what diff's table says it is.
A doc that drifts from the code fails CI (docs/development.md#docs-that-match-the-code).
"""
import re
import subprocess
import sys
from pathlib import Path


def fail(problems, message):
    problems.append(message)
    print("docs_test: " + message)


def cmake_arrows(source):
    text = (source / "CMakeLists.txt").read_text()
    arrows = {}
    for m in re.finditer(r"^set\(SHADOWCERT_ALLOWED_(\w+)([^)]*)\)", text, re.M):
        arrows[m.group(1)] = set(m.group(2).split())
    return arrows


def parse_uses(text, module, modules):
    """A "may use" cell: a comma list, 'nothing', 'everything' or 'all of the above'; anything
    in parentheses (third-party libraries) is not a module."""
    text = re.sub(r"\([^)]*\)", "", text).strip()
    if text in ("nothing", ""):
        return set()
    if text in ("everything", "all of the above"):
        return set(modules) - {module}
    return {word.strip().strip("`/") for word in text.split(",") if word.strip()}


def check_modules(source, problems):
    arrows = cmake_arrows(source)
    if not arrows:
        fail(problems, "no SHADOWCERT_ALLOWED_ line in CMakeLists.txt")
        return
    for module in arrows:
        if not (source / module / "CMakeLists.txt").is_file():
            fail(problems, f"module {module}: no {module}/CMakeLists.txt")
    # README: the ```text block of "name/  description  -> uses" lines.
    readme = (source / "README.md").read_text()
    listed = {}
    for m in re.finditer(r"^(\w+)/\s+.*?->\s*(.+)$", readme, re.M):
        listed[m.group(1)] = parse_uses(m.group(2), m.group(1), arrows)
    # docs/development.md: | `name/` | `target` | what | uses |
    development = (source / "docs" / "development.md").read_text()
    table = {}
    targets = {}
    for m in re.finditer(r"^\| `(\w+)/` \| `([\w]+)`[^|]*\|[^|]*\| ([^|]+) \|$", development, re.M):
        table[m.group(1)] = parse_uses(m.group(3), m.group(1), arrows)
        targets[m.group(1)] = m.group(2)
    for where, found in (("README.md", listed), ("docs/development.md", table)):
        for module, uses in arrows.items():
            if module not in found:
                fail(problems, f"{where}: module {module}/ is missing from its module table")
            elif found[module] != uses:
                fail(problems, f"{where}: {module}/ may use {sorted(found[module])}, "
                               f"CMakeLists.txt says {sorted(uses)}")
    for module, target in targets.items():
        expected = "shadowcert" if module == "cli" else f"shadowcert_{module}"
        if module in arrows and target != expected:
            fail(problems, f"docs/development.md: {module}/'s target is {target}, the build's is {expected}")


def run_help(cli, *words):
    run = subprocess.run([cli, *words, "--help"], capture_output=True, text=True, timeout=60)
    if run.returncode != 0:
        raise RuntimeError(f"{cli} {' '.join(words)} --help exited {run.returncode}: {run.stderr}")
    return run.stdout


def help_subcommands(text):
    """CLI11's subcommand block: '  name  description' lines after 'Subcommands:'."""
    block = re.split(r"^subcommands:$", text, maxsplit=1, flags=re.M | re.I)
    if len(block) < 2:
        return []
    names = []
    for line in block[1].splitlines():
        m = re.match(r"^  (\w[\w-]*)\s", line)
        if m:
            names.append(m.group(1))
    return names


def help_options(text):
    """Every long option CLI11 lists in an OPTIONS block (its lines start with spaces, then the
    option names; description lines are indented further and are not options)."""
    options = set()
    for line in text.splitlines():
        m = re.match(r"^  ((?:-\w,\s*)?--[\w-]+(?:,\s*--[\w-]+)*)", line)
        if m:
            options |= set(re.findall(r"--[\w-]+", m.group(1)))
    options.discard("--help")
    return options


def doc_sections(cli_md):
    """docs/cli.md's '## `shadowcert SUB ...`' sections (### subsections included) as text."""
    sections = {}
    current = None
    for line in cli_md.splitlines():
        m = re.match(r"^## `shadowcert (\w+)", line)
        if m:
            current = m.group(1)
            sections.setdefault(current, "")
        elif line.startswith("## "):
            current = None
        if current:
            sections[current] += line + "\n"
    return sections


def documented_options(section):
    """The options the section documents: the first cell of every table row and the headings."""
    options = set()
    for line in section.splitlines():
        if line.startswith("| "):
            first = line.split("|")[1]
            options |= set(re.findall(r"(--[a-z][\w-]*)", first))
        elif line.startswith("#"):
            options |= set(re.findall(r"(--[a-z][\w-]*)", line))
    return options


def check_options(cli, source, problems):
    cli_md = (source / "docs" / "cli.md").read_text()
    sections = doc_sections(cli_md)
    subcommands = help_subcommands(run_help(cli))
    if len(subcommands) < 5:
        fail(problems, f"shadowcert --help lists only {subcommands}")
    for sub in subcommands:
        if sub not in sections:
            fail(problems, f"docs/cli.md: no section for `shadowcert {sub}`")
            continue
        in_help = help_options(run_help(cli, sub))
        in_doc = documented_options(sections[sub])
        mentioned = set(re.findall(r"(--[a-z][\w-]*)", sections[sub]))
        for option in sorted(in_help - mentioned):
            fail(problems, f"docs/cli.md: `shadowcert {sub}` does not document {option} (in its --help)")
        for option in sorted(in_doc - in_help):
            fail(problems, f"docs/cli.md: `shadowcert {sub}` documents {option}, which its --help does not have")
    for sub in sections:
        if sub not in subcommands:
            fail(problems, f"docs/cli.md: a section for `shadowcert {sub}`, which `shadowcert --help` does not list")


def check_method_names(cli, source, problems):
    cli_md = (source / "docs" / "cli.md").read_text()
    heading = re.search(r"^## `shadowcert render SCENE --method ([\w|-]+)", cli_md, re.M)
    if heading is None:
        fail(problems, "docs/cli.md: the render heading does not list the methods (--method a|b|...)")
        return
    documented = heading.group(1).split("|")
    help_text = run_help(cli, "render")
    listed = re.search(r"--method TEXT:\{([^}]*)\}", help_text)
    if listed is None:
        fail(problems, "shadowcert render --help does not list --method's values as {a,b,...}")
        return
    in_help = [name.strip() for name in listed.group(1).split(",")]
    if documented != in_help:
        fail(problems, f"docs/cli.md's render methods {documented} != render --help's {in_help}")


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    cli, source = sys.argv[1], Path(sys.argv[2])
    problems = []
    check_modules(source, problems)
    check_options(cli, source, problems)
    check_method_names(cli, source, problems)
    print(f"docs_test: {len(problems)} mismatches")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
