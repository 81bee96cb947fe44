"""The mass rules: the paper's redistribution (eqs 1-4), the rules of the lumping literature, their
registry and files, and what a rule's matrix must satisfy.

Layers and the map of moved modules: ARCHITECTURE.md.
"""
