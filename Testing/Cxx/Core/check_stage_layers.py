"""Checks that the core's stages depend on each other one way only.

Reads the list the build writes (Filters/Core/CMakeLists.txt: each stage and the stages it may
use), then every #include "cbc3d/<stage>/..." in every core file. A file may include headers of
its own stage and of the stages its stage DEPENDS on, directly or through them; nothing else.
Also fails when a core file lies outside every stage folder, or a stage list names a stage that
has no folder, so a new folder cannot slip past the check.

usage: check_stage_layers.py STAGE_LIST CORE_DIR
"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"cbc3d/([^"/]+)/[^"]+"', re.MULTILINE)


def read_stages(path):
    stages = {}
    for line in pathlib.Path(path).read_text().splitlines():
        name, _, uses = line.partition(":")
        stages[name.strip()] = uses.split(";") if uses.strip() else []
    return {name: [u.strip() for u in uses if u.strip()] for name, uses in stages.items()}


def reachable(stages, name):
    seen, todo = {name}, [name]
    while todo:
        for used in stages[todo.pop()]:
            if used not in seen:
                seen.add(used)
                todo.append(used)
    return seen


def problems(stages, core):
    found = []
    for name, uses in stages.items():
        for used in uses:
            if used not in stages:
                found.append(f"stage {name} depends on unknown stage {used}")
        if not (core / name).is_dir():
            found.append(f"stage {name} has no folder {core / name}")
    for path in sorted(core.rglob("*")):
        if path.suffix not in (".h", ".cxx"):
            continue
        stage = path.relative_to(core).parts[0]
        if stage not in stages:
            found.append(f"{path}: not in a stage folder")
            continue
        allowed = reachable(stages, stage)
        for included in INCLUDE.findall(path.read_text()):
            if included not in allowed:
                found.append(f"{path}: stage {stage} includes stage {included}, which it does not depend on")
    return found


def main():
    stages = read_stages(sys.argv[1])
    core = pathlib.Path(sys.argv[2])
    if not stages:
        print(f"no stages in {sys.argv[1]}")
        return 1
    found = problems(stages, core)
    for line in found:
        print(line)
    if found:
        return 1
    files = sum(1 for p in core.rglob("*") if p.suffix in (".h", ".cxx"))
    print(f"{len(stages)} stages, {files} files: every include runs down the stage order")
    return 0


if __name__ == "__main__":
    sys.exit(main())
