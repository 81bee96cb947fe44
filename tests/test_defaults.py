"""The light values in :mod:`dispersion.defaults` are the ones the package enforces (issue 23).

The command line reads limits from ``defaults`` so that ``--help`` loads neither numpy nor
sympy; each is checked here against the module that enforces it. Name lists are not copied
into ``defaults`` at all: they are read from their registries (issue 28).
"""
from __future__ import annotations

from fractions import Fraction

import sympy

from dispersion import defaults


def test_no_name_list_is_copied_into_defaults():
    from dispersion.mass_rules.mass import CONTACT_SETS

    for copy in ("MASS_VARIANTS", "TIME_SCHEMES", "TIMESTEP_MODELS", "MODELS"):
        assert not hasattr(defaults, copy), copy
    assert defaults.CONTACT_SETS == CONTACT_SETS


def test_plate_limits_are_the_patch_checks():
    from dispersion.errors import InputError
    from dispersion.symbolic import patch, plate

    assert (plate.P_MAX, plate.N_MAX) == (defaults.P_MAX, defaults.N_MAX)
    assert defaults.R_RANGE == (Fraction(1, 1000), Fraction(1000))
    # the limits are the ones the patch enforces: each bound holds, one past it is refused
    assert patch.check_size(defaults.P_MAX, defaults.P_MAX + 1) == (defaults.P_MAX,
                                                                    defaults.P_MAX + 1)
    lo, hi = (sympy.Rational(r.numerator, r.denominator) for r in defaults.R_RANGE)
    assert (patch.aspect_ratio(lo), patch.aspect_ratio(hi)) == (lo, hi)
    refused = [lambda: patch.check_size(defaults.P_MAX + 1, defaults.P_MAX + 2),
               lambda: patch.check_size(2, defaults.N_MAX + 1),
               lambda: patch.aspect_ratio(lo / 2), lambda: patch.aspect_ratio(hi * 2)]
    for call in refused:
        try:
            call()
        except InputError:
            continue
        raise AssertionError("a value past a limit was not refused")


def test_scheme_and_model_names_are_one_registry():
    from dispersion.time_stepping import fully_discrete, timestep
    from dispersion.time_stepping.time_integration import CRITICAL_STEP_MODELS, NEWMARK_MEMBERS

    for name, (beta, gamma) in NEWMARK_MEMBERS.items():
        scheme = fully_discrete.time_scheme(name)
        assert (scheme.beta, scheme.gamma) == (beta, gamma)
    assert timestep.CRITICAL_STEP_MODELS is CRITICAL_STEP_MODELS


def test_reproduce_and_sweep_defaults():
    from dispersion import sweep
    from dispersion.report import run

    assert (run.DEFAULT_OUT, run.DEFAULT_REFERENCE) == (defaults.REPORT_OUT,
                                                        defaults.REPORT_REFERENCE)
    assert sweep.MAX_JOBS_PER_CPU == run.MAX_JOBS_PER_CPU == defaults.MAX_JOBS_PER_CPU


def test_claims_job_limit_is_the_verifiers():
    from dispersion.claims import limits, verify

    assert verify.MAX_JOBS == limits.MAX_JOBS
    assert verify.check_jobs(limits.MAX_JOBS) == limits.MAX_JOBS
