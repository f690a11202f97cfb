"""The effect catalogue: which Effect classes a plant config may switch on, as an object that is passed.

An :class:`EffectCatalogue` is an ordered mapping name -> Effect class (docs/effects.md). The order is
the order of registration; it fixes the order of the terms in a generated kernel and of the sensor
stages, so the same catalogue gives the same signals bit for bit.

- :func:`builtin_catalogue`: the nominal model's effects, the built-in catalogue and the effects of
  installed packages (entry-point group ``backlash_monitor.effects``). Built once, on first use, and
  never changed afterwards (it refuses ``register``).
- A user's plug-in files go into a *new* catalogue: ``builtin_catalogue().with_files([path, ...])``
  (``--effects-file`` of the commands, ``effects_files`` of the plant_simulator node, a workbench
  model's ``effect_files``). Nothing registers into a shared catalogue.
- A plant config carries the catalogue its effect names were validated against
  (``load_plant_config(..., catalogue=cat)`` -> ``cfg.catalogue``; default: the built-in one);
  the simulator, the kernel choice and the workbench ask the config (or the model) for it.

Importing a plug-in file is memoised by its path and content (``_FILE_CLASSES``): two catalogues
built from the same file hold the same classes (and so share one compiled kernel, whose cache key is
the terms' source anyway); an edited file is imported again.
"""
from __future__ import annotations

import difflib
import hashlib
import importlib.util
import sys
from pathlib import Path
import importlib.metadata

from .effects import CATALOGUE, ENTRY_POINT_GROUP, NOMINAL, Effect, term_source_or_none, validate_effect

_BUILTIN: "EffectCatalogue | None" = None     # the built-in catalogue, built on first use, then frozen
_FILE_CLASSES: dict = {}                      # (resolved path, sha256 of its bytes) -> its Effect classes


class EffectCatalogue:
    """An ordered name -> Effect class mapping (see the module docstring).

    Reads as a mapping (``cat[name]``, ``name in cat``, ``cat.items()``, ``list(cat)``); ``get(name)``
    raises a ValueError naming the nearest known effect and the allowed ones."""

    def __init__(self, classes=()):
        self._classes: dict = {}
        self._files: list = []          # resolved paths of the plug-in files loaded, in order
        self._frozen = False
        for c in classes:
            self.register(c)

    # ------------------------------------------------------------------ building
    def register(self, cls, replace: bool = False):
        """Add an effect class (validated); returns the class (usable as a decorator). The same class, or
        one with the same term and parameters (the same file loaded twice), is not added again; another
        class under a registered name is refused unless ``replace``."""
        self._check_mutable()
        validate_effect(cls)
        old = self._classes.get(cls.name)
        if old is not None and old is not cls and not replace:
            if term_source_or_none(old) == term_source_or_none(cls) and old.parameters == cls.parameters:
                return old           # the same file loaded twice
            raise ValueError(f"effect {cls.name!r} is already registered (by {old.__module__}); allowed: a new name")
        self._classes[cls.name] = cls
        return cls

    def load_effects_file(self, path) -> list:
        """Import a user's Python file and register every Effect subclass defined in it (all or none);
        returns their names. The term sources are read from the file (they become part of the
        generated kernels' cache key)."""
        self._check_mutable()
        classes = _file_classes(path)
        before = dict(self._classes)
        try:
            for c in classes:
                self.register(c)
        except ValueError:
            self._classes = before
            raise
        resolved = Path(path).resolve()
        if resolved not in self._files:
            self._files.append(resolved)
        return [c.name for c in classes]

    def load_entry_points(self) -> list:
        """Register the effects of installed packages (entry-point group ``backlash_monitor.effects``;
        each entry point names an Effect subclass or a module holding them); returns their names."""
        self._check_mutable()
        names = []
        for ep in importlib.metadata.entry_points(group=ENTRY_POINT_GROUP):
            obj = ep.load()
            for c in [obj] if isinstance(obj, type) else _classes_in(obj):
                self.register(c)
                names.append(c.name)
        return names

    def copy(self) -> "EffectCatalogue":
        """A new, changeable catalogue holding the same classes in the same order."""
        new = EffectCatalogue()
        new._classes = dict(self._classes)
        new._files = list(self._files)
        return new

    def with_files(self, paths) -> "EffectCatalogue":
        """A new catalogue: this one plus the effects of the user's plug-in files ``paths`` (this one is
        not changed). No files: a frozen catalogue is returned as it is."""
        paths = [p for p in (paths or ()) if str(p)]
        if not paths and self._frozen:
            return self
        new = self.copy()
        for p in paths:
            new.load_effects_file(p)
        return new

    def freeze(self) -> "EffectCatalogue":
        """Refuse every later change (register, load_*); returns self."""
        self._frozen = True
        return self

    @property
    def frozen(self) -> bool:
        return self._frozen

    def _check_mutable(self) -> None:
        if self._frozen:
            raise ValueError("this effect catalogue is shared and cannot change (the built-in one is used by every "
                             "config without plug-ins); allowed: a new catalogue, catalogue.copy() or "
                             "catalogue.with_files([FILE.py])")

    # ------------------------------------------------------------------ reading
    @property
    def names(self) -> tuple:
        return tuple(self._classes)

    @property
    def files(self) -> tuple:
        """The plug-in files loaded into this catalogue (resolved paths, in order)."""
        return tuple(self._files)

    def get(self, name: str):
        """The effect class ``name``; ValueError naming the nearest known effect and the allowed ones."""
        cls = self._classes.get(name)
        if cls is None:
            near = difflib.get_close_matches(str(name), list(self._classes), n=1)
            raise ValueError(f"unknown effect {name!r}" + (f" (nearest: {near[0]!r})" if near else "")
                             + "; allowed: " + ", ".join(self._classes))
        return cls

    def enabled(self, cfg, kind: str | None = None) -> list:
        """The switched-on effect classes of a plant config (catalogue order), optionally of one kind.
        A switched-on effect this catalogue does not hold is an error (the config was validated against
        another catalogue: use ``cfg.catalogue``)."""
        switches = cfg.effects
        foreign = [n for n, on in switches.items() if on and n not in self._classes]
        if foreign:
            raise ValueError(f"effect {foreign[0]!r} is switched on in the config but not in this catalogue; allowed: "
                             "the catalogue the config was validated against (cfg.catalogue)")
        return [c for n, c in self._classes.items() if switches.get(n, False) and (kind is None or c.kind == kind)]

    def as_dict(self) -> dict:
        return dict(self._classes)

    def __getitem__(self, name):
        return self._classes[name]

    def __contains__(self, name) -> bool:
        return name in self._classes

    def __iter__(self):
        return iter(self._classes)

    def __len__(self) -> int:
        return len(self._classes)

    def keys(self):
        return self._classes.keys()

    def values(self):
        return self._classes.values()

    def items(self):
        return self._classes.items()

    def __repr__(self) -> str:
        what = "built-in" if self is _BUILTIN else f"{len(self._files)} plug-in file(s)"
        return f"<EffectCatalogue {len(self._classes)} effects, {what}>"

    # ------------------------------------------------------------------ copying and pickling
    def __copy__(self):
        return self if self._frozen else self.copy()

    def __deepcopy__(self, memo):
        return self.__copy__()       # the classes themselves are never copied

    def __reduce__(self):
        """Pickled as what it was built from: the built-in catalogue by reference; another as the built-in
        one (when it holds all of it) plus its plug-in files (imported again) plus classes registered by
        hand (pickled by reference), in its own order."""
        if self is _BUILTIN:
            return (builtin_catalogue, ())
        base = builtin_catalogue()
        from_base = all(self._classes.get(n) is c for n, c in base.items())
        from_files = {c for p in self._files for c in _file_classes(p)}
        extra = tuple(c for n, c in self._classes.items()
                      if not (from_base and base._classes.get(n) is c) and c not in from_files)
        return (_rebuild, (from_base, tuple(str(p) for p in self._files), extra, tuple(self._classes),
                           self._frozen))


def _rebuild(from_base: bool, files, extra, order, frozen) -> EffectCatalogue:
    cat = builtin_catalogue().copy() if from_base else EffectCatalogue()
    for p in files:
        cat.load_effects_file(p)
    for c in extra:
        cat.register(c, replace=True)
    cat._classes = {n: cat._classes[n] for n in order}
    return cat.freeze() if frozen else cat


def builtin_catalogue() -> EffectCatalogue:
    """The built-in catalogue: NOMINAL + CATALOGUE + installed entry points (loaded on the first call); shared
    and frozen."""
    global _BUILTIN
    if _BUILTIN is None:
        cat = EffectCatalogue(NOMINAL + CATALOGUE)
        cat.load_entry_points()
        _BUILTIN = cat.freeze()
    return _BUILTIN


def enabled_effects(cfg, kind: str | None = None) -> list:
    """The switched-on effect classes of a config, from its own catalogue (``cfg.catalogue.enabled``)."""
    return cfg.catalogue.enabled(cfg, kind)


def kernel_effect_set(cfg) -> tuple:
    """Names of the compiled (term) effects of a config: what one generated kernel is built for."""
    return tuple(c.name for c in enabled_effects(cfg, "term"))


def _classes_in(namespace) -> list:
    out = []
    for obj in list(vars(namespace).values()) if not isinstance(namespace, dict) else list(namespace.values()):
        if isinstance(obj, type) and issubclass(obj, Effect) and obj is not Effect and getattr(obj, "name", ""):
            if obj.__module__ == getattr(namespace, "__name__", obj.__module__):
                out.append(obj)
    return out


def _file_classes(path) -> tuple:
    """The Effect subclasses a user's file defines (imported once per path and content)."""
    p = Path(path)
    if not p.is_file():
        raise ValueError(f"effects file {str(p)!r} does not exist; allowed: a Python file defining Effect subclasses")
    resolved = p.resolve()
    content = hashlib.sha256(resolved.read_bytes()).hexdigest()
    key = (str(resolved), content)
    classes = _FILE_CLASSES.get(key)
    if classes is not None:
        return classes
    digest = hashlib.sha256(str(resolved).encode()).hexdigest()[:12]
    mod_name = f"_backlash_monitor_user_effects_{digest}_{content[:8]}"
    if resolved.suffix != ".py":
        raise ValueError(f"effects file {str(p)!r} is not a Python file; allowed: a .py file defining Effect "
                         "subclasses (docs/effects.md)")
    spec = importlib.util.spec_from_file_location(mod_name, resolved)
    module = importlib.util.module_from_spec(spec)
    sys.modules[mod_name] = module
    try:
        spec.loader.exec_module(module)
    except SyntaxError as exc:
        sys.modules.pop(mod_name, None)
        raise ValueError(f"effects file {str(p)!r}, line {exc.lineno}: invalid Python ({exc.msg})") from None
    except Exception as exc:  # noqa: BLE001 - a user's file: report, do not trace back
        sys.modules.pop(mod_name, None)
        raise ValueError(f"effects file {str(p)!r} failed to import: {exc}") from None
    classes = tuple(_classes_in(module))
    if not classes:
        raise ValueError(f"effects file {str(p)!r} defines no Effect subclass with a name; allowed: "
                         "classes deriving from backlash_monitor.plant.effects.Effect")
    _FILE_CLASSES[key] = classes
    return classes
