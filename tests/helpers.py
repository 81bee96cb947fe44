"""Helpers shared by several test modules (imported as ``from helpers import ...``; pytest puts
``tests/`` on the path as it does for ``mp_pencil``)."""
from __future__ import annotations

import hashlib
import os
import subprocess
import sys
from pathlib import Path


def snapshot(root: Path) -> dict:
    """Every path under ``root`` with its kind, content, mode and owner: a link its target, a
    folder its mode, a file the SHA-256 of its bytes and its mode (so a changed permission
    counts), a pipe or device its kind; each with its owner (uid, gid). Links are not
    followed and pipes never opened."""
    import stat

    out = {}
    for dirpath, dirnames, filenames in os.walk(root, followlinks=False):
        for name in dirnames + filenames:
            path = Path(dirpath) / name
            rel = str(path.relative_to(root))
            st = os.lstat(path)
            owner = (st.st_uid, st.st_gid)
            if stat.S_ISLNK(st.st_mode):
                out[rel] = ("link", os.readlink(path), owner)
            elif stat.S_ISDIR(st.st_mode):
                out[rel] = ("dir", oct(st.st_mode & 0o7777), owner)
            elif stat.S_ISREG(st.st_mode):
                out[rel] = ("file", hashlib.sha256(path.read_bytes()).hexdigest(),
                            oct(st.st_mode & 0o7777), owner)
            else:
                out[rel] = ("special", oct(st.st_mode), owner)
    return out


def lean_series(argv: list[str]) -> tuple[int, bool, str]:
    """Run ``dispersion.cli.series.lean_main(argv)`` in a fresh interpreter; return its exit
    status, whether sympy was imported on the way, and what it printed."""
    code = ("import sys, io, json, contextlib\n"
            "from dispersion.cli.series import lean_main\n"
            "buf = io.StringIO()\n"
            "with contextlib.redirect_stdout(buf):\n"
            f"    rc = lean_main({argv!r})\n"
            "print(json.dumps([rc, 'sympy' in sys.modules, buf.getvalue()]))\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    import json

    rc, sympy_loaded, out = json.loads(proc.stdout)
    return rc, sympy_loaded, out
