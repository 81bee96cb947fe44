"""Dynamic contact: Kane's contact-modified Newmark, its singular-mass version, the ring and
the Signorini bar. ``dispersion.contact.nurbs`` moved to :mod:`dispersion.splines.nurbs` (the
finite mesh shares it); the old path still imports, with a DeprecationWarning."""
from dispersion._moved import install

install()
