"""A small, fast CDR (XCDR1, as ROS 2 / Fast DDS write it) (de)serialiser driven by `.msg` specs.

Layout rules implemented (they give the same bytes as `rclpy.serialization.serialize_message`, see
test_bag_cdr.py): a 4-byte encapsulation header (00 01 00 00 = CDR little endian; 00 00 = big endian
is read too), then the fields in order; every primitive is aligned to its own size (1, 2, 4, 8)
counted from the first byte after the header; a string is a uint32 length (bytes incl. the trailing
NUL), the UTF-8 bytes and the NUL; a sequence `T[]`/`T[<=N]` is a uint32 count then the elements; a
fixed array `T[N]` is the elements alone; the elements of a primitive array are aligned once, before
the first element, and only when there is at least one element. Primitive arrays are
numpy arrays (`np.frombuffer` / `tobytes`), so a 1000-sample float64[] costs one memcpy.

Decoded messages are `RosMessage` objects (attribute access, `to_dict()`, `==`), one generated class
per type; primitive arrays are numpy arrays, string arrays lists of str, nested arrays lists.
Encoding accepts `RosMessage`s, any object with the field attributes (e.g. rclpy messages) or dicts.
"""
from __future__ import annotations

import struct
from collections.abc import Mapping
from typing import Any

import numpy as np

from .errors import CdrError, UnknownSchemaError
from .schema import PRIMITIVES, Field, MsgSpec, local_specs, parse_schema, normalize_type_name

CDR_LE_HEADER = b"\x00\x01\x00\x00"

_STRUCT_FMT = {k: v[0] for k, v in PRIMITIVES.items()}
_DTYPES_LE = {k: np.dtype("<" + v[0]) if v[1] > 1 else np.dtype(v[0]) for k, v in PRIMITIVES.items()}
_DTYPES_BE = {k: np.dtype(">" + v[0]) if v[1] > 1 else np.dtype(v[0]) for k, v in PRIMITIVES.items()}
_DTYPES_LE["bool"] = _DTYPES_BE["bool"] = np.dtype("?")


# ----------------------------------------------------------------------------------------------
# Message objects


class RosMessage:
    """Base of generated message classes: attributes = fields, `__msgtype__` = 'pkg/msg/Name'."""

    __slots__ = ()
    __msgtype__ = ""
    __fields__: tuple[str, ...] = ()

    def __init__(self, **kwargs):
        for name in self.__fields__:
            object.__setattr__(self, name, kwargs.pop(name, None))
        if kwargs:
            raise TypeError(f"{self.__msgtype__} has no field(s) {sorted(kwargs)}")

    def __repr__(self) -> str:
        inner = ", ".join(f"{n}={_short_repr(getattr(self, n))}" for n in self.__fields__)
        return f"{self.__msgtype__}({inner})"

    def __eq__(self, other) -> bool:
        if not isinstance(other, RosMessage) or other.__msgtype__ != self.__msgtype__:
            return NotImplemented
        return all(_value_eq(getattr(self, n), getattr(other, n)) for n in self.__fields__)

    __hash__ = None  # mutable

    def to_dict(self) -> dict[str, Any]:
        """Plain Python (lists, floats, ints, strs): for JSON and comparisons."""
        return {n: _to_plain(getattr(self, n)) for n in self.__fields__}


def _short_repr(v) -> str:
    if isinstance(v, np.ndarray):
        return f"array(shape={v.shape}, dtype={v.dtype})"
    return repr(v)


def _value_eq(a, b) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        return a.shape == b.shape and bool(np.array_equal(a, b, equal_nan=a.dtype.kind == "f"))
    if isinstance(a, float) and isinstance(b, float) and a != a and b != b:
        return True
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_value_eq(x, y) for x, y in zip(a, b))
    return a == b


def _to_plain(v):
    if isinstance(v, RosMessage):
        return v.to_dict()
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, list):
        return [_to_plain(x) for x in v]
    if isinstance(v, np.generic):
        return v.item()
    return v


_CLASSES: dict[tuple[str, tuple], type] = {}


def message_class(spec: MsgSpec) -> type:
    """The generated RosMessage subclass of a spec (cached by name and field names)."""
    names = tuple(f.name for f in spec.fields)
    key = (spec.name, names)
    cls = _CLASSES.get(key)
    if cls is None:
        short = spec.name.rsplit("/", 1)[-1]
        cls = type(short, (RosMessage,), {"__slots__": names, "__msgtype__": spec.name,
                                           "__fields__": names})
        _CLASSES[key] = cls
    return cls


# ----------------------------------------------------------------------------------------------
# Codec


class Codec:
    """Encoder/decoder of one message type, from its parsed specs.

    >>> codec = Codec.for_type("backlash_monitor_msgs/msg/SignalChunk")
    >>> msg = codec.decode(cdr_bytes); msg.samples  # numpy float64 array
    >>> codec.encode(msg) == cdr_bytes
    """

    def __init__(self, type_name: str, specs: Mapping[str, MsgSpec]):
        self.type_name = normalize_type_name(type_name)
        if self.type_name not in specs:
            raise UnknownSchemaError(f"no definition of {self.type_name!r} in the schema")
        self.specs = dict(specs)
        self.classes = {name: message_class(spec) for name, spec in self.specs.items()}
        for spec in self.specs.values():
            for f in spec.fields:
                if f.type == "wstring":
                    raise UnknownSchemaError(
                        f"{spec.name}.{f.name}: wstring fields are not supported")
        self._fast = None
        if _is_signal_chunk(self.specs, self.type_name):
            c = self.classes
            self._fast_classes = (c["std_msgs/msg/Header"], c["builtin_interfaces/msg/Time"],
                                  c[self.type_name])
            self._fast = self._dec_signal_chunk_le
        self._fast_encode = None
        if _has_shape(self.specs, self.type_name, _BACKLASH_ESTIMATE_SHAPE):
            self._fast_encode = self._enc_backlash_estimate

    @classmethod
    def for_type(cls, type_name: str) -> "Codec":
        """Codec of an installed type (definition found as `schema.full_definition` finds it)."""
        return cls(type_name, local_specs(type_name))

    @classmethod
    def from_schema(cls, type_name: str, text: str, encoding: str = "ros2msg") -> "Codec":
        return cls(type_name, parse_schema(type_name, text, encoding))

    # ------------------------------------------------------------------ defaults
    def new(self, type_name: str | None = None, **fields) -> RosMessage:
        """A message with every field at its default (0, '', empty array, nested defaults)."""
        spec = self.specs[type_name or self.type_name]
        values = {}
        for f in spec.fields:
            if f.name in fields:
                values[f.name] = fields.pop(f.name)
            else:
                values[f.name] = self._default(f)
        if fields:
            raise TypeError(f"{spec.name} has no field(s) {sorted(fields)}")
        return self.classes[spec.name](**values)

    def _default(self, f: Field):
        if f.is_array:
            n = f.array_size or 0
            if f.is_primitive:
                return np.zeros(n, dtype=_DTYPES_LE[f.type])
            if f.is_string:
                return [""] * n
            return [self.new(f.type) for _ in range(n)]
        if f.is_primitive:
            return False if f.type == "bool" else (0.0 if f.type.startswith("float") else 0)
        if f.is_string:
            return ""
        return self.new(f.type)

    # ------------------------------------------------------------------ decode
    def decode(self, data) -> RosMessage:
        mv = memoryview(data)
        if len(mv) < 4:
            raise CdrError(f"{self.type_name}: CDR payload of {len(mv)} bytes has no header")
        kind = mv[1]
        if mv[0] != 0 or kind not in (0, 1):
            raise CdrError(f"{self.type_name}: unsupported CDR encapsulation "
                           f"{bytes(mv[:2]).hex()} (only plain CDR, little or big endian)")
        little = kind == 1
        if little and self._fast is not None:
            try:
                return self._fast(mv)
            except Exception:  # noqa: BLE001 - malformed: the generic decoder names the problem
                pass
        try:
            msg, _ = self._dec(self.specs[self.type_name], mv, 4, little)
        except (struct.error, ValueError, IndexError) as exc:
            raise CdrError(f"{self.type_name}: payload does not match the definition: {exc}") from None
        return msg

    @property
    def is_signal_chunk(self) -> bool:
        """True when the type has SignalChunk's layout: :meth:`signal_chunk_fields` applies."""
        return self._fast is not None

    def signal_chunk_fields(self, mv, copy: bool = True, strings: list | None = None) -> tuple | None:
        """(sec, nanosec, frame_id, signal_name, unit, sample_period_s, first_sample_index,
        samples) of a SignalChunk-shaped little-endian payload, without message objects (the
        fields ``decode`` puts into the message); None when the payload is not plain
        little-endian CDR. Raises on a malformed payload (``decode`` then names the problem).
        ``copy=False``: samples is a view of ``mv``'s buffer (no allocation; it keeps the
        buffer alive and is read-only when the buffer is).
        ``strings``: a one-item list kept by the caller per topic; it remembers the last
        payload's string section (frame_id, signal_name, unit: the same in every message of a
        topic) and a payload whose section has the same bytes reuses its strings unparsed."""
        if len(mv) < 4 or mv[0] != 0 or mv[1] != 1:
            return None
        size = len(mv)
        sec, nanosec = _TIME_LE.unpack_from(mv, 4)
        known = strings[0] if strings is not None else None
        if known is not None and mv[12:known[4]] == known[0]:
            _raw, frame_id, signal_name, unit, pos = known
        else:
            frame_id, pos = _dec_string(mv, 12, "<")
            signal_name, pos = _dec_string(mv, pos, "<")
            unit, pos = _dec_string(mv, pos, "<")
            if strings is not None:
                strings[0] = (bytes(mv[12:pos]), frame_id, signal_name, unit, pos)
        pos += (-(pos - 4)) & 7
        period, first = _F64_U64_LE.unpack_from(mv, pos)
        pos += 16
        (n,) = _U32_LE.unpack_from(mv, pos)   # pos - 4 is a multiple of 8 here: aligned
        pos += 4
        if n:
            pos += 4                            # float64 alignment
            end = pos + 8 * n
            if end > size:
                raise CdrError("samples run past the end")
            samples = np.frombuffer(mv[pos:end], dtype=_F64_LE)
            if copy:
                samples = samples.copy()
        else:
            samples = np.zeros(0, dtype=_F64_LE)
        return sec, nanosec, frame_id, signal_name, unit, period, first, samples

    def _dec_signal_chunk_le(self, mv):
        """Straight-line little-endian decoder of SignalChunk-shaped specs (header, 2 strings, float64,
        uint64, float64[]): the same message as ``_dec`` (test_analyze_fast_decode.py checks it
        field by field), about 6x faster. Raises on anything unusual; ``decode`` then falls back."""
        sec, nanosec, frame_id, signal_name, unit, period, first, samples = \
            self.signal_chunk_fields(mv)
        # the generated classes have no __init__ logic beyond setting every slot: set them directly
        header_cls, time_cls, msg_cls = self._fast_classes
        stamp = time_cls.__new__(time_cls)
        stamp.sec = sec
        stamp.nanosec = nanosec
        header = header_cls.__new__(header_cls)
        header.stamp = stamp
        header.frame_id = frame_id
        msg = msg_cls.__new__(msg_cls)
        msg.header = header
        msg.signal_name = signal_name
        msg.unit = unit
        msg.sample_period_s = period
        msg.first_sample_index = first
        msg.samples = samples
        return msg

    def _dec(self, spec: MsgSpec, mv, pos: int, little: bool):
        e = "<" if little else ">"
        dtypes = _DTYPES_LE if little else _DTYPES_BE
        values = {}
        for f in spec.fields:
            if f.is_array:
                if f.array_size is not None:
                    n = f.array_size
                else:
                    pos += (-(pos - 4)) & 3
                    (n,) = struct.unpack_from(e + "I", mv, pos)
                    pos += 4
                if f.is_primitive:
                    dt = dtypes[f.type]
                    size = dt.itemsize
                    if n:
                        if size > 1:
                            pos += (-(pos - 4)) & (size - 1)
                        end = pos + n * size
                        if end > len(mv):
                            raise CdrError(f"{spec.name}.{f.name}: array of {n} runs past the end")
                        arr = np.frombuffer(mv[pos:end], dtype=dt).copy()
                        pos = end
                    else:
                        arr = np.zeros(0, dtype=dt)
                    if not little and size > 1:
                        arr = arr.astype(arr.dtype.newbyteorder("<"))
                    values[f.name] = arr
                elif f.is_string:
                    out = []
                    for _ in range(n):
                        s, pos = _dec_string(mv, pos, e)
                        out.append(s)
                    values[f.name] = out
                else:
                    sub = self.specs[f.type]
                    out = []
                    for _ in range(n):
                        m, pos = self._dec(sub, mv, pos, little)
                        out.append(m)
                    values[f.name] = out
            elif f.is_primitive:
                fmt = _STRUCT_FMT[f.type]
                size = PRIMITIVES[f.type][1]
                if size > 1:
                    pos += (-(pos - 4)) & (size - 1)
                (v,) = struct.unpack_from(e + fmt, mv, pos)
                pos += size
                values[f.name] = v
            elif f.is_string:
                values[f.name], pos = _dec_string(mv, pos, e)
            else:
                values[f.name], pos = self._dec(self.specs[f.type], mv, pos, little)
        return self.classes[spec.name](**values), pos

    # ------------------------------------------------------------------ encode
    #: value of the alignment padding bytes (0; tests set another value to locate the padding)
    pad_byte = 0

    def encode(self, msg) -> bytes:
        """CDR little-endian bytes of `msg` (header included, no trailing padding)."""
        if self._fast_encode is not None:
            try:
                return self._fast_encode(msg)
            except (_NotFast, AttributeError, KeyError, TypeError, ValueError, struct.error):
                pass   # the generic encoder gives the same bytes or names the problem
        out = bytearray(CDR_LE_HEADER)
        self._enc(self.specs[self.type_name], msg, out)
        return bytes(out)

    def _enc_backlash_estimate(self, msg) -> bytes:
        """Straight-line encoder of BacklashEstimate-shaped specs (the estimates ``analyze``
        writes): the generic encoder's bytes (test_bag_fast_encode.py checks them byte for byte),
        several times faster. Raises _NotFast for a value it does not take as is (None = the
        default, bytes/char forms, bytes arrays); ``encode`` then uses the generic encoder."""
        pad = self.pad_byte
        header = _get(msg, "header")
        stamp = _get(header, "stamp")
        out = bytearray(CDR_LE_HEADER)
        out += _TIME_LE.pack(_get(stamp, "sec"), _get(stamp, "nanosec"))
        _enc_string(out, pad, _get_str(header, "frame_id"))
        _enc_string(out, pad, _get_str(msg, "signal_name"))
        _enc_string(out, pad, _get_str(msg, "mode"))
        _pad(out, pad, 8)
        out += _U64_LE.pack(_get(msg, "entry_sample_index"))
        _enc_string(out, pad, _get_str(msg, "entry_kind"))
        for name in ("candidate_widths_m", "b_vector"):
            arr = _get_f64_array(msg, name)
            _pad(out, pad, 4)
            out += _U32_LE.pack(len(arr))
            if len(arr):
                _pad(out, pad, 8)
                out += arr.tobytes()
        _pad(out, pad, 4)
        out += _U32_LE.pack(_get(msg, "width_index"))
        _pad(out, pad, 8)
        out += _F64X4_LE.pack(_get(msg, "width_m"), _get(msg, "b_margin"),
                              _get(msg, "continuous_width_m"), _get(msg, "fused_width_m"))
        out += _U32_LE.pack(_get(msg, "fused_events"))
        _pad(out, pad, 8)
        out += _F64X3_LE.pack(_get(msg, "true_width_m"), _get(msg, "fused_continuous_width_m"),
                              _get(msg, "fused_width_uncertainty_m"))
        return bytes(out)

    def _enc(self, spec: MsgSpec, msg, out: bytearray) -> None:
        get = msg.get if isinstance(msg, Mapping) else (lambda k, d=None: getattr(msg, k, d))
        for f in spec.fields:
            v = get(f.name, None)
            if v is None:
                v = self._default(f)
            if f.is_array:
                n = len(v)
                if f.array_size is not None:
                    if n != f.array_size:
                        raise CdrError(f"{spec.name}.{f.name}: needs {f.array_size} elements, got {n}")
                else:
                    if f.upper_bound is not None and n > f.upper_bound:
                        raise CdrError(f"{spec.name}.{f.name}: {n} elements > bound {f.upper_bound}")
                    _pad(out, self.pad_byte, 4)
                    out += struct.pack("<I", n)
                if f.is_primitive:
                    dt = _DTYPES_LE[f.type]
                    if n:
                        if isinstance(v, (list, tuple)) and v and isinstance(v[0], (bytes, bytearray)):
                            v = b"".join(v)
                        if isinstance(v, (bytes, bytearray, memoryview)):
                            arr = np.frombuffer(v, dtype=np.uint8).astype(dt, copy=False)
                        else:
                            arr = np.asarray(v, dtype=dt)
                        if dt.itemsize > 1:
                            _pad(out, self.pad_byte, dt.itemsize)
                        out += arr.tobytes()
                elif f.is_string:
                    for s in v:
                        _enc_string(out, self.pad_byte, s)
                else:
                    sub = self.specs[f.type]
                    for item in v:
                        self._enc(sub, item, out)
            elif f.is_primitive:
                size = PRIMITIVES[f.type][1]
                if isinstance(v, (bytes, bytearray)):  # rclpy 'byte' fields are bytes of length 1
                    v = v[0]
                elif isinstance(v, str):  # rclpy 'char' fields are 1-char strings
                    v = ord(v)
                if size > 1:
                    _pad(out, self.pad_byte, size)
                out += struct.pack("<" + _STRUCT_FMT[f.type], v)
            elif f.is_string:
                _enc_string(out, self.pad_byte, v)
            else:
                self._enc(self.specs[f.type], v, out)


_TIME_LE = struct.Struct("<iI")
_F64_U64_LE = struct.Struct("<dQ")
_U32_LE = struct.Struct("<I")
_F64_LE = np.dtype("<f8")

_HEADER_SHAPE = {
    "std_msgs/msg/Header": (("stamp", "builtin_interfaces/msg/Time", False),
                            ("frame_id", "string", False)),
    "builtin_interfaces/msg/Time": (("sec", "int32", False), ("nanosec", "uint32", False)),
}

_SIGNAL_CHUNK_SHAPE = {
    "": (("header", "std_msgs/msg/Header", False), ("signal_name", "string", False),
         ("unit", "string", False), ("sample_period_s", "float64", False),
         ("first_sample_index", "uint64", False), ("samples", "float64", True)),
    **_HEADER_SHAPE,
}
_U64_LE = struct.Struct("<Q")
_F64X4_LE = struct.Struct("<dddd")
_F64X2_LE = struct.Struct("<dd")
_F64X3_LE = struct.Struct("<ddd")

_BACKLASH_ESTIMATE_SHAPE = {
    "": (("header", "std_msgs/msg/Header", False), ("signal_name", "string", False),
         ("mode", "string", False), ("entry_sample_index", "uint64", False),
         ("entry_kind", "string", False), ("candidate_widths_m", "float64", True),
         ("b_vector", "float64", True), ("width_index", "uint32", False),
         ("width_m", "float64", False), ("b_margin", "float64", False),
         ("continuous_width_m", "float64", False), ("fused_width_m", "float64", False),
         ("fused_events", "uint32", False), ("true_width_m", "float64", False),
         ("fused_continuous_width_m", "float64", False),
         ("fused_width_uncertainty_m", "float64", False)),
    **_HEADER_SHAPE,
}


def _has_shape(specs: Mapping[str, MsgSpec], type_name: str, shapes) -> bool:
    """True when `type_name` has exactly the layout `shapes` (any package/name): a fast path."""
    for name, shape in shapes.items():
        spec = specs.get(name or type_name)
        if spec is None or len(spec.fields) != len(shape):
            return False
        for f, (fname, ftype, is_array) in zip(spec.fields, shape):
            if (f.name, f.type, f.is_array) != (fname, ftype, is_array) or f.array_size is not None \
                    or f.upper_bound is not None or f.string_bound is not None:
                return False
    return True


def _is_signal_chunk(specs: Mapping[str, MsgSpec], type_name: str) -> bool:
    """True when `type_name` has exactly SignalChunk's layout (any package/name): the fast path."""
    return _has_shape(specs, type_name, _SIGNAL_CHUNK_SHAPE)


class _NotFast(Exception):
    """A value the straight-line encoder does not take as is: the generic encoder takes over."""


def _value(obj, name: str):
    """obj[name] of a dict / Mapping, else obj.name (as the generic encoder reads fields)."""
    if type(obj) is dict or isinstance(obj, Mapping):
        return obj[name]
    return getattr(obj, name)


def _get(obj, name: str):
    v = _value(obj, name)
    if v is None or isinstance(v, (str, bytes, bytearray)):
        raise _NotFast(name)     # default values, rclpy byte/char forms: the generic rules
    return v


def _get_str(obj, name: str):
    v = _value(obj, name)
    if type(v) is not str:
        raise _NotFast(name)
    return v


def _get_f64_array(obj, name: str) -> np.ndarray:
    v = _value(obj, name)
    if v is None or isinstance(v, (bytes, bytearray, memoryview)) or (
            isinstance(v, (list, tuple)) and v and isinstance(v[0], (bytes, bytearray))):
        raise _NotFast(name)
    return np.asarray(v, dtype=_F64_LE)


def _pad(out: bytearray, pad_byte: int, align: int) -> None:
    rem = (len(out) - 4) & (align - 1)
    if rem:
        out += bytes((pad_byte,)) * (align - rem)


def _enc_string(out: bytearray, pad_byte: int, s) -> None:
    b = s.encode("utf-8") if isinstance(s, str) else bytes(s)
    _pad(out, pad_byte, 4)
    out += struct.pack("<I", len(b) + 1)
    out += b
    out += b"\x00"


def _dec_string(mv, pos: int, e: str):
    pos += (-(pos - 4)) & 3
    (n,) = struct.unpack_from(e + "I", mv, pos)
    pos += 4
    if n == 0:  # some writers send 0 for an empty string
        return "", pos
    end = pos + n
    if end > len(mv):
        raise CdrError(f"string of {n} bytes runs past the end of the payload")
    raw = bytes(mv[pos:end - 1]) if mv[end - 1] == 0 else bytes(mv[pos:end])
    return raw.decode("utf-8", errors="replace"), end
