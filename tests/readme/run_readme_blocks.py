#!/usr/bin/env python3
"""The README's Python examples and shell sessions, run as they are written.

  run_readme_blocks.py python README.md
      Every ```python block: a block of ">>> " lines is run as a doctest (each result must be
      the one shown under it, whitespace aside); any other block is run as a script. The
      package is imported from PYTHONPATH (the build's build/python).
  run_readme_blocks.py shell README.md CERTCYL_BINARY_DIR
      Every shell session: an indented block (4 spaces) whose lines start with "$ " are commands
      and the lines under each, its expected standard output. A command goes on over the next
      lines while its quoting is open or it ends in a backslash; an output line that begins
      with a space continues the line above it (a long JSON line wrapped for reading: the space
      and the break are not part of the output). Each command runs in bash in a scratch folder,
      with CERTCYL_BINARY_DIR first on PATH, and must print exactly its output within 30 s (its
      exit status is not checked: `certcyl query` exits 2 after an error line; a signal fails). Indented commands without "$ " (long runs, files of the reader's own) are not run.

Exit status 1 on the first difference, naming the README line.
"""
import doctest
import os
import pathlib
import re
import shlex
import subprocess
import sys
import tempfile


def python_blocks(lines):
    """(line number of the first code line, code) of every ```python block."""
    blocks, i = [], 0
    while i < len(lines):
        if lines[i].rstrip() == "```python":
            start = i + 1
            j = start
            while j < len(lines) and lines[j].rstrip() != "```":
                j += 1
            if j == len(lines):
                sys.exit(f"README.md:{i + 1}: the ```python block is not closed")
            blocks.append((start + 1, "\n".join(lines[start:j]) + "\n"))
            i = j
        i += 1
    return blocks


def run_python(readme):
    lines = readme.read_text().splitlines()
    blocks = python_blocks(lines)
    if not blocks:
        sys.exit("FAILED: README.md has no ```python block")
    for first, code in blocks:
        where = f"README.md:{first}"
        if re.search(r"^>>> ", code, re.M):
            test = doctest.DocTestParser().get_doctest(code, {}, where, str(readme), first - 1)
            runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
            runner.run(test)
            if runner.failures or not test.examples:
                sys.exit(f"FAILED: {where}: {runner.failures} of {len(test.examples)} examples print something else")
            print(f"{where}: {len(test.examples)} examples as in the README")
        else:
            try:
                exec(compile(code, where, "exec"), {"__name__": "__readme__"})
            except Exception as e:  # any failure of the example is the test's failure
                sys.exit(f"FAILED: {where}: the block raised {type(e).__name__}: {e}")
            print(f"{where}: the block ran")


def complete(command):
    """True when the shell command's quoting is closed and it does not end in a backslash."""
    if command.rstrip().endswith("\\"):
        return False
    try:
        shlex.split(command)
    except ValueError:
        return False
    return True


def sessions(lines):
    """(line number, command, expected output) of every "$ " command of the indented blocks."""
    found, i = [], 0
    while i < len(lines):
        line = lines[i]
        if not line.startswith("    $ ") or (i > 0 and lines[i - 1].startswith("    ")):
            i += 1
            continue
        # An indented block starting with a command.
        while i < len(lines) and lines[i].startswith("    $ "):
            first = i + 1
            command = lines[i][6:]
            i += 1
            while not complete(command) and i < len(lines) and lines[i].startswith("    "):
                command += "\n" + lines[i][4:]
                i += 1
            output = []
            while i < len(lines) and lines[i].startswith("    ") and not lines[i].startswith("    $ "):
                text = lines[i][4:]
                if text.startswith(" ") and output:
                    output[-1] += text.lstrip()
                else:
                    output.append(text)
                i += 1
            found.append((first, command, "".join(o + "\n" for o in output)))
    return found


def run_shell(readme, binary_dir):
    lines = readme.read_text().splitlines()
    found = sessions(lines)
    if not found:
        sys.exit("FAILED: README.md has no shell session (an indented block of \"$ \" commands)")
    env = dict(os.environ, PATH=f"{os.path.abspath(binary_dir)}{os.pathsep}{os.environ.get('PATH', '')}")
    with tempfile.TemporaryDirectory(prefix="certcyl_readme_") as scratch:
        for first, command, expected in found:
            where = f"README.md:{first}"
            try:
                r = subprocess.run(["bash", "-c", command], cwd=scratch, env=env, capture_output=True, text=True, timeout=30)
            except subprocess.TimeoutExpired:
                sys.exit(f"FAILED: {where}: the command ran longer than 30 s:\n{command}")
            if r.returncode < 0:
                sys.exit(f"FAILED: {where}: the command was ended by signal {-r.returncode}:\n{command}\n{r.stdout}{r.stderr}")
            if r.stdout != expected:
                sys.exit(f"FAILED: {where}: the command\n{command}\nprinted (exit status {r.returncode})\n{r.stdout}"
                         f"{r.stderr}instead of the README's\n{expected}")
            print(f"{where}: output as in the README")


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "python":
        run_python(pathlib.Path(sys.argv[2]))
    elif len(sys.argv) == 4 and sys.argv[1] == "shell":
        run_shell(pathlib.Path(sys.argv[2]), sys.argv[3])
    else:
        sys.exit(__doc__)
