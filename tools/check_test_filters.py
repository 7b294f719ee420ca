#!/usr/bin/env python3
"""Checks that ctest runs every Catch2 test case of the given test executables.

catch_discover_tests registers one ctest test per TEST_CASE name and runs the executable with
that name as its filter. Seven cases once passed in every CI run without running: six names
held a ";" (CMake's list separator cut them short, so the filter matched nothing and Catch2
exited 0) and one began with "--" (Catch2 read it as an option and printed its usage). This
check runs each executable once per name, with the name escaped as CatchAddTests.cmake does,
and requires the filter to list exactly that one case.

usage: check_test_filters.py TEST_EXECUTABLE...
"""
import subprocess
import sys


def names_of(executable):
    out = subprocess.run([executable, "--list-test-names-only"], capture_output=True, text=True,
                         timeout=120).stdout
    return [line for line in out.splitlines() if line.strip()]


def catch_filter(name):
    # CatchAddTests.cmake escapes these before passing the name as a test spec.
    for char in ",[]":
        name = name.replace(char, "\\" + char)
    return name


def problems_of(executable):
    problems = []
    names = names_of(executable)
    if not names:
        problems.append(f"{executable}: lists no test cases")
    for name in names:
        if ";" in name:
            problems.append(f"{executable}: '{name}' holds a ';' (CMake splits the name there)")
            continue
        if name.startswith("-"):
            problems.append(f"{executable}: '{name}' starts with '-' (Catch2 reads an option)")
            continue
        listed = subprocess.run([executable, "--list-test-names-only", catch_filter(name)],
                                capture_output=True, text=True, timeout=120).stdout
        matched = [line for line in listed.splitlines() if line.strip()]
        if matched != [name]:
            problems.append(f"{executable}: the filter for '{name}' lists {len(matched)} "
                            f"case(s): {matched[:3]}")
    return len(names), problems


def main(argv):
    if len(argv) < 2:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    total, problems = 0, []
    for executable in argv[1:]:
        count, found = problems_of(executable)
        total += count
        problems += found
    for p in problems:
        print(p)
    print(f"{total} test cases in {len(argv) - 1} executables; {len(problems)} not run as "
          f"registered")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
