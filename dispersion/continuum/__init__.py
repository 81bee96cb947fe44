"""The continuum: exact plate models (a layered or anisotropic plate as a value, its exact
dispersion relation, and every mode of it found and certified)."""
