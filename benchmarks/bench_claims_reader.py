"""Worst cases of a claims coefficient within the reader's limits.

A coefficient that passes :func:`dispersion.claims.reader.check_size` is read, factored for
display (:func:`dispersion.claims.schema.readable`) and compared with a derived coefficient
(:func:`dispersion.claims.describe_difference`), against a series in nu alone and one in nu
and the symbolic aspect ratio r. The cases sit at the limits (terms, bits, degree) and mix
symbols and long numbers, the inputs that made factoring take minutes before the limits.

Run:  python benchmarks/bench_claims_reader.py

Prints one line per case and the worst total time; the limits' rule is "about a second".
"""
from __future__ import annotations

import time

from dispersion.claims import describe_difference, reader
from dispersion.claims.schema import readable
from dispersion.symbolic.power_balance import discrete_series
from dispersion.continuum.exact_series import exact_series

N60 = "9" * 59 + "7"
N20 = "98765432109876543211"
CASES = [
    f"({N60}+nu)^18", f"({N60}+nu)^19", "(1+nu+r)^9", f"({N20}+{N20}3*nu+{N20}7*r)^9",
    "(1+nu)^63", "(1+nu)^31*(1+r)", "(1+nu)^63/(1-nu)^63", f"(1+{N20}*nu)^30*(1+r)",
    "+".join(f"{N20}{k}/(nu+{k})" for k in range(1, 5)),
    "+".join(f"{N20}{k}*r/(nu+{k}*r)" for k in range(1, 5)),
    f"(({N20}+nu)^5*(1+r)^2)/((3+nu*r)^4)", "(2+nu+r)^7/(3+nu-r)^7",
]


def main() -> None:
    references = {"exact S0 kappa^6 (nu)": exact_series("S0", 6)[6],
                  "bloch A0 kappa^6 (nu, r)": discrete_series("A0", 6, model="bloch")[6]}
    worst = 0.0
    for case in CASES:
        for label, derived in references.items():
            start = time.perf_counter()
            printed = readable(reader.read(case))
            describe_difference(printed, derived)
            seconds = time.perf_counter() - start
            worst = max(worst, seconds)
            print(f"{seconds:6.2f} s  {case[:60]:60s} vs {label}")
    print(f"worst: {worst:.2f} s (limits: terms {reader.MAX_TERMS}, bits {reader.MAX_BITS}, "
          f"degree {reader.MAX_DEGREE})")


if __name__ == "__main__":
    main()
