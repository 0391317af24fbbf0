"""tools/bench-compare as a Python module, for the tools that share its helpers (the CPU line
every report names, its number formats, its FGC benchmark parameters). bench-compare is a
script without a .py suffix, so a plain import does not find it."""
import importlib.machinery
import importlib.util
import os


def load():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bench-compare")
    loader = importlib.machinery.SourceFileLoader("bench_compare", path)
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader("bench_compare", loader))
    loader.exec_module(module)
    return module
