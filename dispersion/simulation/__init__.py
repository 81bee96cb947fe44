"""Guided-wave simulation: a plate strip, explicit dynamics, and the exact reference.

One burst (:mod:`.tone_burst`) sent along a plane-strain strip (:mod:`.strip`, assembled by
:mod:`.strip_mesh` for any rule of the mass registry), integrated by central differences
(:mod:`.central_difference`, with the mass of :mod:`.mass_operator` and the step of
:mod:`.mesh_critical_step`), compared with the exact Rayleigh-Lamb modal synthesis
(:mod:`.modal_synthesis`, :mod:`.signal_error`) and with what the dispersion analysis
predicts (:mod:`.dispersion_prediction`); :func:`.wave_run.simulate` runs all of it, bounded
up front (:mod:`.run_cost`). The wing sits beside :mod:`dispersion.contact`: it imports
:mod:`dispersion.symbolic` and :mod:`dispersion.waves` only.
"""
