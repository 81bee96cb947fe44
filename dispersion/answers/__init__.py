"""The answers of the commands: the tables that `dispersion branches`, `series` and `timestep` print
and the Lamb-wave calculator's tables (isotropic and layered plates), with the physical units they
convert to.

Layers and the map of moved modules: ARCHITECTURE.md.
"""
