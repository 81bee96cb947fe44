"""``dispersion branches --exact --evanescent``: the evanescent modes of a plate (one isotropic
layer or a layup) at the frequencies of ``--frequency``/``--fd``.

Calls :func:`dispersion.api.evanescent_modes`, renders the table and draws its figure
(:func:`dispersion.plotting.evanescent.figure_evanescent`).
"""
from __future__ import annotations


def run(args, plate, thickness_mm=None) -> int:
    """The evanescent modes of ``plate`` (a layered plate, or an isotropic material with
    ``thickness_mm``)."""
    from dispersion.api import evanescent_modes
    from dispersion.cli.options import families, frequencies
    from dispersion.cli.outputs import check_outputs, warn_failures, write_outputs

    check_outputs(args, "branches")
    if args.fd is not None:
        freq = {"fd_mhz_mm": frequencies(args.fd, "--fd", units=None)}
    else:
        freq = {"frequency_khz": frequencies(args.frequency, "--frequency")}
    bound = {} if args.decay_max is None else {"decay_db": args.decay_max}
    table = evanescent_modes(plate, thickness_mm=thickness_mm, families=families(args),
                             **bound, **freq)
    warn_failures(table, args)
    write_outputs(args, table, _figure)
    return 0


def _figure(table):
    from dispersion.plotting.evanescent import figure_evanescent

    return figure_evanescent(table)
