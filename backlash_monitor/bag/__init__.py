"""Record/replay storage: rosbag2-compatible MCAP files (`ros2 bag info/play`, Foxglove, rosbags).

- `BagWriter` / `BagReader` (writer.py, reader.py): the files; see docs/bags.md.
- `Codec` (cdr.py): CDR (de)serialisation with numpy arrays; `schema.full_definition` /
  `schema.parse_schema`: ros2msg schema text.
- errors.py: `BagError` and its subclasses.
"""
from .cdr import Codec, RosMessage
from .errors import (BagError, CdrError, CorruptBagError, DamagedBagError, MissingTopicError,
                     NotABagError,
                     TruncatedBagError, UnknownSchemaError)
from .reader import BagMessage, BagReader, DamagedChunk, RecoveryReport, SignalSeries, TopicInfo
from .schema import full_definition, parse_schema, type_hash
from .writer import BagWriter, qos_profile

# The project's topics and their types (SPEC section 2).
SIGNAL_CHUNK = "backlash_monitor_msgs/msg/SignalChunk"
BACKLASH_WINDOW = "backlash_monitor_msgs/msg/BacklashWindow"
BACKLASH_ESTIMATE = "backlash_monitor_msgs/msg/BacklashEstimate"
DIAGNOSTIC_ARRAY = "diagnostic_msgs/msg/DiagnosticArray"

__all__ = [
    "BagError", "BagMessage", "BagReader", "BagWriter", "CdrError", "Codec", "CorruptBagError",
    "DamagedBagError", "DamagedChunk",
    "MissingTopicError", "NotABagError", "RecoveryReport", "RosMessage", "SignalSeries",
    "TopicInfo", "TruncatedBagError", "UnknownSchemaError", "full_definition", "parse_schema",
    "qos_profile", "type_hash", "SIGNAL_CHUNK", "BACKLASH_WINDOW", "BACKLASH_ESTIMATE",
    "DIAGNOSTIC_ARRAY",
]
