"""`pip install .` of the checkout, offline, into a scratch target folder, and the installed
package imported from there (not from the build tree) and answering a query.

    /usr/bin/python3 tests/python/test_pip_install.py SOURCE_DIR WORK_DIR

The CMake build of the install is WORK_DIR/pip-build/cmake (kept between runs, so a second run
rebuilds only what changed); CMAKE_ARGS is passed on to it (the test passes the flags of the
project's build so that ccache serves the objects it compiled).
"""
import os
import shutil
import subprocess
import sys
import unittest
from pathlib import Path

SOURCE = WORK = None  # from the command line


class PipInstall(unittest.TestCase):
    def test_install_into_a_target_and_import(self):
        target = WORK / "target"
        shutil.rmtree(target, ignore_errors=True)
        env = dict(os.environ, CERTCYL_PIP_BUILD_DIR=str(WORK / "pip-build"), PIP_NO_INPUT="1")
        env.pop("PYTHONPATH", None)
        done = subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation", "--no-deps", "--no-index",
                               "--no-cache-dir", "--disable-pip-version-check", "--target", str(target), str(SOURCE)],
                              env=env, capture_output=True, text=True)
        errors = [l for l in (done.stdout + done.stderr).splitlines() if "error" in l.lower()]
        self.assertEqual(done.returncode, 0, "\n".join(errors[:40]) + "\n" + done.stderr[-3000:])
        modules = list((target / "certcyl").glob("_certcyl*.so"))
        self.assertEqual(len(modules), 1, list(target.rglob("*")))
        self.assertTrue((target / "certcyl" / "__init__.py").is_file())
        metadata = list(target.glob("certcyl-*.dist-info/METADATA"))
        self.assertEqual(len(metadata), 1)
        text = metadata[0].read_text()
        self.assertIn("Name: certcyl", text)
        self.assertIn("Version: 0.1.0", text)
        self.assertIn("Requires-Dist: numpy", text)
        # The installed package, alone on the path: a line through the axis, one on the wall.
        script = ("import certcyl; print(certcyl.__file__); "
                  "r = certcyl.line_cylinder([[-3, 0, 1], [-3, 1, 1]], [1, 0, 0], [0, 0, 0, 0, 0, 2, 1.0]); "
                  "print(r.answer.tolist(), r.t_in.tolist(), r.t_out.tolist())")
        run = subprocess.run([sys.executable, "-c", script], env=dict(env, PYTHONPATH=str(target)), cwd=str(WORK),
                             capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        where, answers = run.stdout.splitlines()
        self.assertEqual(Path(where), target / "certcyl" / "__init__.py")
        self.assertEqual(answers, "[2, 1] [2.0, 3.0] [4.0, 3.0]")
        # The checkout is left clean: no egg-info or setuptools build folder beside the sources.
        self.assertFalse(list(SOURCE.glob("*.egg-info")) + list((SOURCE / "python").glob("*.egg-info")))


if __name__ == "__main__":
    SOURCE, WORK = Path(sys.argv[1]).resolve(), Path(sys.argv[2]).resolve()
    del sys.argv[1:3]
    WORK.mkdir(parents=True, exist_ok=True)
    unittest.main()
