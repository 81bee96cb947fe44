"""``dispersion ring``: the ring benchmark (paper sec. 3) with one mass variant.

Examples::

    dispersion ring --mass singular --json
    dispersion ring --mass lumped --level 1 --dt 0.025 --t-end 30 --out results/ring
"""
from __future__ import annotations

import argparse
import json
import sys
from dataclasses import replace

from ..contact.scenario import Scenario
from ..errors import InputError
from . import number

DEFAULT = Scenario()

MASSES = ("lumped", "singular", "consistent")


def register(sub) -> None:
    p = sub.add_parser("ring", help="ring bouncing on a rigid plane (paper Figure 4)",
                       description="Quarter ring (one quadratic NURBS patch) bouncing on a "
                                   "rigid frictionless plane; contact-modified Newmark; "
                                   "reconstructed scenario (see dispersion.contact.scenario).")
    p.add_argument("--mass", choices=MASSES, default="singular")
    p.add_argument("--scheme", choices=("kane", "standard"), default="kane",
                   help="Newmark variant: contact-modified (Kane, default) or standard")
    p.add_argument("--level", type=int, default=0,
                   help="mesh refinement level: 16*2^level x 2*2^level elements")
    p.add_argument("--dt", type=number("dt"), default=None,
                   help=f"time step (s), default {DEFAULT.dt:g}")
    p.add_argument("--t-end", type=number("t-end"), default=None,
                   help=f"end time (s), default {DEFAULT.t_end:g}")
    p.add_argument("--out", help="write summary.json, history.csv, figure.png into DIR")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    p.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="tqdm progress bar on stderr (default: on a terminal)")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..contact.simulate import simulate_ring
    from ..io import write_text

    if isinstance(args.level, bool) or args.level < 0 or args.level > 4:
        raise InputError(f"level must be an integer in [0, 4], got {args.level}")
    sc = DEFAULT.with_level(args.level)
    changes = {k: v for k, v in (("dt", args.dt), ("t_end", args.t_end)) if v is not None}
    sc = replace(sc, **changes)
    show = sys.stderr.isatty() if args.progress is None else args.progress
    bar = None
    if show:
        from tqdm import tqdm

        bar = tqdm(total=sc.n_steps, desc=f"ring {args.mass}", unit="step", file=sys.stderr)
    try:
        res = simulate_ring(sc, args.mass, args.scheme,
                            progress=bar.update if bar is not None else None)
    finally:
        if bar is not None:
            bar.close()
    if args.out:
        from pathlib import Path

        from ..io import save_figure
        from ..plotting.ring import plot_contact_energy

        out = Path(args.out)
        write_text(out / "summary.json", json.dumps(res.to_dict()["summary"], indent=1))
        write_text(out / "result.json", json.dumps(res.to_dict()))
        write_text(out / "history.csv", res.csv_text())
        ax = plot_contact_energy(res)
        save_figure(ax.figure, out / "figure.png", dpi=120)
    if args.json:
        print(json.dumps(res.summary, indent=1))
    else:
        s = res.summary
        print(f"ring ({s['mass']} mass, {s['scheme']}): energy change "
              f"{s['energy_change_percent']:+.3f} %, max penetration {s['max_penetration']:.3e} m, "
              f"{s['contact_events']} contact events, rotation {s['final_rotation_deg']:.1f} deg")
    return 0
