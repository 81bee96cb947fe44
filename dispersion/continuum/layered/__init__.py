"""Layered and anisotropic plates, the continuum's second model: a plate as a value
(``layered_plate``: layers of any elastic law, spring interfaces, a direction, layup strings;
``layup_file``: the same from a stranger's TOML file), its exact relation (``stroh``: the
partial waves of one layer; ``dynamic_stiffness``: the stiffness determinant of the stack and
its Wittrick-Williams count), the B-spline SAFE pencil that finds every candidate (``safe``),
and every mode found and certified: at a frequency (``layered_modes``), at a wavenumber
(``layered_branches``), damped (``damped_modes``), at its zero group velocity points
(``layered_zgv``).

Layers and the map of moved modules: ARCHITECTURE.md.
"""
