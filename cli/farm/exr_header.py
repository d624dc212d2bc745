"""The attributes of an OpenEXR file's header, read without reading pixels: what `tray-farm
status` needs of each part (tray:status, tray:pixelsDone, tray:job). Layout from the OpenEXR
file format ("The OpenEXR File Layout", openexr.com): magic 20000630, a 4-byte version, then
attributes `name\\0 type\\0 size:int32 value` until an empty name."""

import struct

MAGIC = 20000630


def read_attributes(path):
    """The string and float attributes of the first header of `path` as a dict; None if the
    file is missing, not an EXR or truncated (a part still being written looks like that)."""
    try:
        with open(path, "rb") as f:
            data = f.read(1 << 20)  # headers are small; TRay's are a few kB
    except OSError:
        return None
    if len(data) < 8 or struct.unpack_from("<i", data, 0)[0] != MAGIC:
        return None
    attributes, at = {}, 8
    try:
        while True:
            end = data.index(b"\0", at)
            name = data[at:end].decode("utf-8", "replace")
            if not name:
                return attributes
            type_end = data.index(b"\0", end + 1)
            kind = data[end + 1:type_end].decode("ascii", "replace")
            (size,) = struct.unpack_from("<i", data, type_end + 1)
            value = data[type_end + 5:type_end + 5 + size]
            if len(value) != size:
                return None
            if kind == "string":
                attributes[name] = value.decode("utf-8", "replace")
            elif kind == "float" and size == 4:
                attributes[name] = struct.unpack("<f", value)[0]
            at = type_end + 5 + size
    except (ValueError, struct.error):
        return None


def part_state(path):
    """'missing', 'partial N%' or 'complete' for a part file written by tray-render."""
    attributes = read_attributes(path)
    if attributes is None:
        return "missing"
    if attributes.get("tray:status") == "complete":
        return "complete"
    total = attributes.get("tray:pixelsTotal") or 1
    return "partial %d%%" % int(100 * attributes.get("tray:pixelsDone", 0) / total)
