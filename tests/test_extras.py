"""Optional extras: a command that needs one it lacks says which, in one line, before any work.

matplotlib (the ``plots`` extra) is hidden from a child process with
``sys.modules['matplotlib'] = None`` (every ``import matplotlib`` then raises ImportError, as
in an install without the extra). The computation each command would start is replaced by a
function that raises, so a check that came after the work would show as a traceback.
"""
from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

from dispersion.plotting import PLOTS_EXTRA

CHILD = textwrap.dedent("""
    import sys, types
    sys.modules["matplotlib"] = None  # an install without the plots extra

    def work_started(*args, **kwargs):
        raise RuntimeError("work started before the extras were checked")

    import dispersion.continuum.exact_branches as eb
    import dispersion.contact.simulate as sim
    import dispersion.contact.signorini as sig
    eb.trace_branches = work_started
    sim.simulate_ring = work_started
    sig.signorini_1d = work_started
    from dispersion.report import SECTIONS
    for name in SECTIONS:
        m = types.ModuleType("dispersion.report." + name)
        m.measure, m.render = work_started, work_started
        sys.modules["dispersion.report." + name] = m
    from dispersion.cli import main
    sys.exit(main(sys.argv[1:]))
""")

# one child process costs a few seconds of start-up: one case runs by default, the rest slow
COMMANDS = [
    pytest.param(["branches", "--figure", "f.png", "--count", "5", "--no-progress"],
                 id="branches --figure"),
    pytest.param(["branches", "--exact", "--figure", "f.png", "--count", "5", "--no-progress"],
                 id="branches --exact --figure", marks=pytest.mark.slow),
    pytest.param(["ring", "--out", "ring", "--t-end", "0.1", "--dt", "0.1", "--no-progress"],
                 id="ring --out", marks=pytest.mark.slow),
    pytest.param(["impact", "signorini-1d", "--figure", "i.png"], id="impact --figure",
                 marks=pytest.mark.slow),
    pytest.param(["reproduce", "--sections", "studies", "--jobs", "1", "--out", "rep"],
                 id="reproduce --sections studies", marks=pytest.mark.slow),
    pytest.param(["reproduce", "--jobs", "1", "--out", "rep"], id="reproduce",
                 marks=pytest.mark.slow),
]


@pytest.mark.parametrize("args", COMMANDS)
def test_missing_plots_extra_is_named_before_any_work(args, tmp_path):
    proc = subprocess.run([sys.executable, "-c", CHILD, *args], cwd=tmp_path,
                          capture_output=True, text=True, check=False)
    assert proc.returncode == 2, proc.stderr
    err = proc.stderr.strip().splitlines()
    assert len(err) == 1 and PLOTS_EXTRA in err[0], proc.stderr
    assert err[0].startswith(f"dispersion {args[0]}: error: ")
    assert list(tmp_path.iterdir()) == []  # nothing written, nothing half-done


@pytest.mark.slow
def test_commands_without_figures_do_not_need_the_extra(tmp_path):
    proc = subprocess.run(
        [sys.executable, "-c", "import sys; sys.modules['matplotlib'] = None\n"
         "from dispersion.cli import main; sys.exit(main(sys.argv[1:]))",
         "impact", "signorini-1d", "--t-end", "3", "--dt", "0.01", "--format", "json"],
        cwd=tmp_path, capture_output=True, text=True, check=False)
    assert proc.returncode == 0, proc.stderr
    assert '"stress_rel_l2"' in proc.stdout
