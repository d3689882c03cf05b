#!/usr/bin/env python3
"""cmake/build_commit.cmake, the commit machine.json records, on a scratch git repository.

  check_build_commit.py CMAKE BUILD_COMMIT_SCRIPT

The header names HEAD's commit (compared with `git rev-parse HEAD` of the scratch repository),
is left untouched (same modification time) when nothing changed, says "+modified" after an edit
of a tracked file but not after an untracked file appears, follows a new commit, and is
"unknown" outside a git checkout. Exit status 1 on the first difference.
"""
import os
import pathlib
import subprocess
import sys
import tempfile


def main():
    cmake, script = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        repo, header = tmp / "repo", tmp / "out" / "certcyl_build_commit.hpp"
        repo.mkdir()

        def git(*args):
            return subprocess.run(["git", "-C", str(repo), "-c", "user.name=t", "-c", "user.email=t@t", *args],
                                  check=True, capture_output=True, text=True).stdout.strip()

        def build(source=repo):
            subprocess.run([cmake, f"-DSOURCE_DIR={source}", f"-DOUTPUT={header}", "-P", script], check=True)
            return header.read_text()

        def expect(text, commit, what):
            line = f'#define CERTCYL_BUILD_COMMIT "{commit}"'
            if line not in text:
                sys.exit(f"FAILED: {what}: expected {line!r} in:\n{text}")

        git("init", "-q")
        (repo / "a.txt").write_text("one\n")
        git("add", "a.txt")
        git("commit", "-q", "-m", "first")
        first = git("rev-parse", "HEAD")
        expect(build(), first, "a clean checkout")
        before = header.stat().st_mtime_ns
        os.utime(header, ns=(before - 10**9, before - 10**9))
        stamped = header.stat().st_mtime_ns
        expect(build(), first, "built again")
        if header.stat().st_mtime_ns != stamped:
            sys.exit("FAILED: the header was rewritten although the commit did not change")
        (repo / "untracked.txt").write_text("x\n")
        expect(build(), first, "an untracked file")
        (repo / "a.txt").write_text("two\n")
        expect(build(), first + "+modified", "a tracked file edited")
        git("commit", "-q", "-am", "second")
        second = git("rev-parse", "HEAD")
        if second == first:
            sys.exit("FAILED: the scratch repository did not get a new commit")
        expect(build(), second, "a new commit")
        outside = tmp / "plain"
        outside.mkdir()
        expect(build(outside), "unknown", "outside a git checkout")
    print("build_commit: OK")


if __name__ == "__main__":
    main()
