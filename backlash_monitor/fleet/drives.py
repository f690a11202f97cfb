"""The drives of a fleet: names, namespaces, hardware ids and each node's parameters.

A fleet is given either as a count (``fleet --drives 8``: drive01..drive08 on line1, the same
plant with seeds 1..8) or as a YAML file (config/fleet.yaml)::

    defaults: {width_m: 0.005, n1: 0.89}     # optional, for every drive
    lines:
      line1:
        drive01: {width_m: 0.004, seed: 1}
        drive02: {}

Drive ``drive07`` of ``line1`` runs in the namespace ``/line1/drive07`` (its topics are
``/line1/drive07/plant/a1``, ``.../estimate``); its diagnostics carry hardware_id
``line1/drive07``, unique in the fleet, and status names ``line1/drive07/<node>: <task>``.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
import os

import yaml

from backlash_monitor.errors import UsageError

# Per-drive keys and the nodes they go to. The values are checked by the nodes themselves (their
# declared ranges, ros/parameters.py); a bad one stops that drive with one clear line.
PLANT_KEYS = ("width_m", "eta_k", "n1", "seed", "noise")
CLASSIFIER_KEYS = ("mode", "n1", "trigger", "fusion_events", "warn_width_m", "error_width_m")
WINDOWING_KEYS = ("trigger",)
TREND_KEYS = ("trend_state_file",)       # width_trend's state_file: the live trend over restarts
WATCH_KEYS = ("watch", "watch_reference", "snapshot_dir")   # the model watch: on/off (default off; fleet
                                                            # --model-watch: on), its model version's reference
                                                            # (default: the default model's at the drive's
                                                            # width_m, eta_k, n1), its snapshot folder
# the drive registry's keys (files/registry.py, docs/registry.md): the fleet file is the registry; a drive's current
# model version, its library (the classifier's) and watch reference, the versions before
REGISTRY_KEYS = ("model", "library", "versions", "registered_utc")
# the signals a simulated drive's windowing node reads (measured angles, a1 checked against the motor speed:
# check_a1_chain): its plant streams once the node subscribes to them all (the pipeline's too). The windowing
# stage's own rule (chain/stage.py input_signals) gives the same list (test_fleet_drives)
SIMULATED_WINDOWING_READS = "windowing:a1,a2,angle_difference,omega1"
DRIVE_KEYS = tuple(sorted(set(PLANT_KEYS + CLASSIFIER_KEYS + WINDOWING_KEYS + TREND_KEYS + WATCH_KEYS
                              + REGISTRY_KEYS)))

NAME_PATTERN = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")   # a ROS name token: namespaces, node names
DEFAULT_LINE = "line1"
DEFAULT_WIDTH_M = 0.005
DEFAULT_ETA_K = 0.025           # the plant_simulator node's defaults (the paper's pattern group)
DEFAULT_N1 = 0.89


@dataclass(frozen=True)
class Drive:
    line: str
    name: str
    parameters: dict = field(default_factory=dict)

    @property
    def namespace(self) -> str:
        return f"/{self.line}/{self.name}"

    @property
    def hardware_id(self) -> str:
        return f"{self.line}/{self.name}"

    @property
    def watched(self) -> bool:
        """The drive runs a model watch: ``watch: true`` in the fleet file, or ``fleet --model-watch`` (which sets
        it on every drive whose file does not say ``watch: false``). Off by default: a watch costs CPU per drive
        (docs/model_watch.md, Cost) and the fleet's real-time capacity is measured without it."""
        return bool(self.parameters.get("watch", False))

    def nominal(self) -> tuple[float, float, float]:
        """The drive's nominal width [m], eta_k [Pa*s^n], n1 [-] (its simulated plant's; the plant_simulator
        node's defaults where the fleet file gives none)."""
        p = self.parameters
        return (float(p.get("width_m", DEFAULT_WIDTH_M)), float(p.get("eta_k", DEFAULT_ETA_K)),
                float(p.get("n1", DEFAULT_N1)))

    def node_parameters(self, duration_s: float = 0.0, rate_factor: float = 1.0) \
            -> dict[str, dict]:
        """{node name: {parameter: value}} for this drive's plant and chain (and model watch)."""
        p = self.parameters
        trigger = p.get("trigger", "contact_loss")
        plant = {k: p[k] for k in PLANT_KEYS if k in p}
        plant.setdefault("width_m", DEFAULT_WIDTH_M)
        # the stream starts once this drive's windowing node takes its four signals (a live
        # view or recorder subscribing first does not start it early)
        plant.update(drive_name=self.hardware_id, rate_factor=float(rate_factor),
                     duration_s=float(duration_s), qos="reliable",
                     wait_for_subscribers=[SIMULATED_WINDOWING_READS])
        # the simulated drive publishes its motor speed: a1 is checked against it (docs/classifier.md 5.4)
        windowing = dict(drive_name=self.hardware_id, qos="reliable", trigger=trigger,
                         width_m=float(plant["width_m"]) if trigger == "paper" else 0.0, check_a1_chain=True)
        classifier = {k: p[k] for k in CLASSIFIER_KEYS if k in p}
        classifier["drive_name"] = self.hardware_id
        versions = p.get("versions")
        classifier["model_version"] = len(versions) + 1 if isinstance(versions, list) else 1   # the registry's
        if p.get("library"):
            classifier["library"] = str(p["library"])
        width, eta_k, n1 = self.nominal()
        watch = {"drive_name": self.hardware_id, "qos": "reliable", "width_m": width, "eta_k": eta_k, "n1": n1,
                 "snapshot_dir": str(p.get("snapshot_dir", ".")),
                 **({"reference": str(p["watch_reference"])} if p.get("watch_reference") else {})}
        return {"plant_simulator": plant, "windowing": windowing, "denoise": {},
                "classifier": classifier, "model_watch": watch,
                "width_trend": {"drive_name": self.hardware_id,
                                **({"fusion_events": int(p["fusion_events"])} if "fusion_events" in p else {}),
                                **({"state_file": str(p["trend_state_file"])}
                                   if p.get("trend_state_file") else {})}}

    def to_dict(self) -> dict:
        return {"line": self.line, "name": self.name, "parameters": dict(self.parameters)}

    @classmethod
    def from_dict(cls, d: dict) -> "Drive":
        return cls(d["line"], d["name"], dict(d.get("parameters", {})))


def _check_name(kind: str, name) -> str:
    if not isinstance(name, str) or not NAME_PATTERN.match(name):
        raise UsageError(f"{kind} name {name!r} is not allowed; allowed: a letter, then letters, "
                         "digits or '_' (it becomes a ROS namespace)")
    return name


def _check_keys(where: str, params) -> dict:
    if params is None:
        return {}
    if not isinstance(params, dict):
        raise UsageError(f"{where}: {params!r} is not a mapping; allowed: {{key: value}} with keys "
                         + ", ".join(DRIVE_KEYS))
    unknown = sorted(set(params) - set(DRIVE_KEYS))
    if unknown:
        raise UsageError(f"{where}: unknown key(s) {', '.join(map(str, unknown))}; allowed: "
                         + ", ".join(DRIVE_KEYS))
    if "watch" in params and not isinstance(params["watch"], bool):
        raise UsageError(f"{where}: watch = {params['watch']!r}; allowed: true or false")
    return dict(params)


def drives_from_count(count: int, line: str = DEFAULT_LINE, width_m: float = DEFAULT_WIDTH_M) \
        -> list[Drive]:
    """drive01..driveNN on ``line``: the same plant, disturbance seeds 1..N."""
    if not isinstance(count, int) or count < 1 or count > 999:
        raise UsageError(f"--drives {count!r}: out of range, allowed 1..999")
    _check_name("line", line)
    digits = max(2, len(str(count)))
    return [Drive(line, f"drive{i:0{digits}d}", {"width_m": width_m, "seed": i})
            for i in range(1, count + 1)]


def drives_from_config(config: dict, source: str = "fleet file") -> list[Drive]:
    """The drives of a parsed fleet YAML (see the module doc)."""
    if not isinstance(config, dict) or not isinstance(config.get("lines"), dict) \
            or not config["lines"]:
        raise UsageError(f"{source}: needs 'lines: {{line1: {{drive01: {{...}}, ...}}}}' with at "
                         "least one line and drive")
    unknown = sorted(set(config) - {"defaults", "lines"})
    if unknown:
        raise UsageError(f"{source}: unknown key(s) {', '.join(map(str, unknown))}; allowed: "
                         "defaults, lines")
    defaults = _check_keys(f"{source}: defaults", config.get("defaults"))
    drives = []
    for line, members in config["lines"].items():
        _check_name("line", line)
        if not isinstance(members, dict) or not members:
            raise UsageError(f"{source}: line {line} lists no drives; allowed: "
                             "{drive01: {...}, ...}")
        for name, params in members.items():
            _check_name("drive", name)
            drives.append(Drive(line, name, {**defaults, **_check_keys(
                f"{source}: {line}/{name}", params)}))
    return drives


def load_drives(path: str) -> list[Drive]:
    try:
        with open(path, encoding="utf-8") as f:
            config = yaml.safe_load(f)
    except OSError as error:
        raise UsageError(f"fleet file {path}: {error.strerror}; give a readable YAML file") from None
    except yaml.YAMLError as error:
        raise UsageError(f"fleet file {path} is not valid YAML: "
                         f"{str(error).splitlines()[0]}") from None
    drives = drives_from_config(config, source=f"fleet file {path}")
    # the registry's paths are relative to the file (docs/registry.md)
    root = os.path.dirname(os.path.abspath(path))
    return [Drive(d.line, d.name, {**d.parameters, **{k: os.path.join(root, d.parameters[k])
                                                       for k in ("model", "library", "watch_reference")
                                                       if isinstance(d.parameters.get(k), str)
                                                       and d.parameters[k]}})
            for d in drives]
