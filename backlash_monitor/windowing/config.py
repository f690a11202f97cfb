"""Windowing constants: defaults (mirrored in config/windowing.yaml) and the YAML loader."""
from __future__ import annotations

import os
from typing import Any, Mapping

import yaml

from backlash_monitor.files.config import config_file, nearest, yaml_error_line

__all__ = ["DEFAULTS", "DEFAULT_CONFIG_PATH", "load_windowing_config", "TRIGGERS", "ANGLE_SOURCES",
           "INTEGRATION_RULES", "KIND_ONSET", "KIND_RETURN", "default_window_offset"]

TRIGGERS = ("contact_loss", "paper")
ANGLE_SOURCES = ("auto", "measured", "integrated")
INTEGRATION_RULES = ("trapezoid", "rectangle")
KIND_ONSET = "onset"
KIND_RETURN = "return"

# Keep in step with config/windowing.yaml (a test checks they agree).
DEFAULTS: dict[str, Any] = {
    "detector": {
        "trigger": "contact_loss",
        "width_m": None,
        "radius_m": 0.15,
        "sample_period_s": 2.0e-5,
        "holdoff_samples": 2048,
        "angle_source": "auto",
        "integration": "trapezoid",
        "confirm_rad": 0.015,
        "reference_tau_s": 0.02,
        "settle_samples": 100,
        "settle_range_rad": 1.5e-3,
        "fit_samples": 2048,
        "contact_deflection_rad": 1.5e-3,
        "initial_contact_side": 1,
        "rereference_interval_s": 0.05,
    },
    "capture": {
        "window_length": 2048,
        "signals": ["a1", "a2"],
        "history_samples": 4096,
        # samples from the detected entry to the window's first sample, per trigger
        "window_offset_samples": {"contact_loss": 200, "paper": 0},
    },
    "sensor_offset": {
        # whole load periods (onset window end to onset window end) averaged per offset estimate
        "periods": 8,
        # |offset| [m/s^2] beyond which the windowing diagnostics say WARN (MEMS zero-g offset ~0.2 g)
        "plausible_abs_m_s2": 2.0,
    },
    "sensors": {
        # |a1|, |a2| [m/s^2] an accelerometer can report (its full scale); beyond: a corrupted sample
        "accelerometer_range_m_s2": 1960.0,
    },
    "saturation": {
        # a signal at its rail (clipped) or stuck at one value (saturation.py; docs/windowing.md)
        "rail_min_run_samples": 3,
        "rail_band_fraction": 0.0025,
        "rail_band_quanta": 4,
        "rail_overpopulation_ratio": 3.0,
        "stuck_min_run_samples": 1000,
        "stuck_quiet_steps": 1,
        "stuck_quiet_max_run_samples": 9500,
        "local_step_levels": 8,
        "local_step_tolerance": 0.1,
        "rail_noise_band_sd": 2.0,
        "rail_noise_shape_z": 4.0,
        "rail_noise_event_gap_samples": 2048,
        "rail_noise_min_visit_samples": 8,
        "block_samples": 50000,
    },
}

# the packaged config/windowing.yaml (files.config: the source tree's, else the installed one)
DEFAULT_CONFIG_PATH = config_file("windowing.yaml")


def load_windowing_config(path: str | os.PathLike | None = None) -> dict[str, Any]:
    """Load ``config/windowing.yaml`` (or ``path``) merged over ``DEFAULTS``.

    Keys not known to DEFAULTS raise ValueError (a typo must not silently fall back to a default).
    Each value in the YAML is ``{value: ..., unit: ..., reason: ...}`` or a plain value.
    """
    if path is None:
        path = DEFAULT_CONFIG_PATH if DEFAULT_CONFIG_PATH.is_file() else None
    cfg = {sec: dict(vals) for sec, vals in DEFAULTS.items()}
    if path is None:
        return cfg
    try:
        with open(path, "r", encoding="utf-8") as fh:
            raw = yaml.safe_load(fh) or {}
    except yaml.YAMLError as error:
        raise ValueError(yaml_error_line(path, error)) from None
    except OSError as error:
        raise ValueError(f"{path}: cannot be read ({error.strerror or error})") from None
    if not isinstance(raw, Mapping):
        raise ValueError(f"{path}: not a mapping of sections (allowed sections: {sorted(cfg)})")
    for sec, vals in raw.items():
        if sec not in cfg:
            raise ValueError(f"{path}: unknown section {sec!r}{nearest(sec, cfg)} "
                             f"(allowed: {sorted(cfg)})")
        if vals is not None and not isinstance(vals, Mapping):
            raise ValueError(f"{path}: section {sec!r} must be a mapping of keys")
        for key, val in (vals or {}).items():
            if key not in cfg[sec]:
                raise ValueError(f"{path}: unknown key {sec}.{key}{nearest(key, cfg[sec])} "
                                 f"(allowed: {sorted(cfg[sec])})")
            if isinstance(val, Mapping) and "value" in val:
                unknown = sorted(set(val) - {"value", "unit", "reason"})
                if unknown:
                    raise ValueError(f"{path}: unknown field {sec}.{key}.{unknown[0]}"
                                     f"{nearest(str(unknown[0]), ('value', 'unit', 'reason'))} "
                                     "(allowed: value, unit, reason)")
                val = val["value"]
            cfg[sec][key] = val
    return cfg


def default_window_offset(trigger: str, config: Mapping[str, Any] | None = None) -> int:
    """The configured window start offset of a trigger (capture.window_offset_samples[trigger])."""
    if trigger not in TRIGGERS:
        raise ValueError(f"unknown trigger {trigger!r}; allowed: {', '.join(TRIGGERS)}")
    cfg = DEFAULTS if config is None else config
    return int(cfg["capture"]["window_offset_samples"][trigger])
