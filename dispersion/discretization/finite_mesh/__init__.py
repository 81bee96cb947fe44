"""The discretization wing: the finite mesh beside the periodic lattice.

* :mod:`.finite_patch`: a finite patch as a value (bar or plate strip, open or periodic ends,
  uniform, graded or perturbed knots, optionally mapped by a NURBS geometry, any mass rule);
* :mod:`.finite_assembly` (and :mod:`.mapped_assembly`): its sparse K and M, the one
  assembly the wave simulation (:mod:`dispersion.simulation`) runs on;
* :mod:`.mesh_pencil`: the pencil the ends and an outlier-removal method leave;
* :mod:`.mesh_spectrum`: every frequency (banded or dense), the top ones (Lanczos), the
  normalized spectrum against the continuum;
* :mod:`.mesh_step`: the stable step of central differences of a mesh, with a proven bound;
* :mod:`.outlier_removal`, :mod:`.outlier_numbers`: the boundary outliers, counted, their
  limit as N grows, and their removal.

The periodic lattice (the Bloch plate patch and the periodic bar) is the other half of the
wing; it still lives in :mod:`dispersion.waves` and :mod:`dispersion.symbolic` until the
layout split moves it here.
"""
