"""Record/replay storage: rosbag2-compatible MCAP files (`ros2 bag info/play`, Foxglove, rosbags).

Layered as the `mcap` package is (docs/bags.md):

- records.py: the MCAP records -- opcodes, fields, build (writer) and parse (reader), chunk
  decompression; summary.py: the footer and summary section;
- index.py: what an open file has (schemas, channels, chunks, counts) from whatever layout it
  uses; integrity.py: the checks, the scan of a damaged file and the RecoveryReport;
  prefetch.py: chunks decompressed ahead in each reader's own worker thread;
- `BagWriter` / `BagReader` (writer.py, reader.py): the files;
- `Codec` (cdr.py): CDR (de)serialisation with numpy arrays; signal_table.py: the fields of a
  topic's many SignalChunk payloads in a file without chunks, at once; `schema.full_definition` /
  `schema.parse_schema`: ros2msg schema text;
- errors.py: `BagError` and its subclasses.
"""
from .cdr import Codec, RosMessage
from .errors import (BagError, CdrError, CorruptBagError, DamagedBagError, MissingTopicError,
                     NotABagError, TruncatedBagError, UnknownSchemaError, UnsupportedBagError)
from .integrity import DamagedChunk, RecoveryReport
from .reader import (BagMessage, BagReader, SignalChunkColumns, SignalChunkRecord, SignalSeries, Stamp,
                     TopicInfo)
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
    "MissingTopicError", "NotABagError", "RecoveryReport", "RosMessage", "SignalChunkColumns", "SignalChunkRecord", "SignalSeries", "Stamp",
    "TopicInfo", "TruncatedBagError", "UnknownSchemaError", "UnsupportedBagError",
    "full_definition", "parse_schema", "qos_profile", "type_hash", "SIGNAL_CHUNK",
    "BACKLASH_WINDOW", "BACKLASH_ESTIMATE", "DIAGNOSTIC_ARRAY",
]
