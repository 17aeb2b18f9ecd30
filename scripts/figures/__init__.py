"""ContactLab's figures, one module per figure (or per close group), found by scanning this package.

Every module here except `common` is a figure module: it declares each figure it draws with
`@figure(experiments=[...], outputs=[...])` (common.py) on a function `draw(results)`. Adding a
figure is adding a module; nothing lists them.
"""
import importlib
import pkgutil

HELPERS = {"common", "generic"}  # modules that hold shared code, or draw for no declared experiment


def figure_modules():
    """The figure modules of this package, imported, in name order."""
    names = sorted(m.name for m in pkgutil.iter_modules(__path__) if m.name not in HELPERS)
    return [importlib.import_module(f"{__name__}.{name}") for name in names]


def figures_of(module):
    """MODULE's declared figures (functions with .experiments and .outputs), in source order."""
    found = [f for f in vars(module).values()
             if callable(f) and hasattr(f, "experiments") and hasattr(f, "outputs") and f.__module__ == module.__name__]
    return sorted(found, key=lambda f: f.__code__.co_firstlineno)


def all_figures():
    """Every declared figure, as (module, function) pairs: modules in name order, each
    module's figures in source order."""
    return [(m, f) for m in figure_modules() for f in figures_of(m)]
