#!/usr/bin/env python3
"""gltf_seeds.py OUT FILE...: packs .gltf / .glb files with their companions
into seeds for tests/fuzz/fuzz_gltf.cpp (its comment has the layout).

Buffers go in as they are; images as a 1x1 PNG (the tool never decodes
them: their size would only slow the fuzzer). A companion that is missing,
outside the file's directory or a data URI is left out."""
import json
import os
import struct
import sys
import urllib.parse

PNG = bytes.fromhex("89504e470d0a1a0a0000000d4948445200000001000000010806000000"
                    "1f15c4890000000d49444154789c6360000002000100e221bc330000000049454e44ae426082")


def document(raw):
    if raw[:4] == b"glTF" and len(raw) >= 20:
        length = struct.unpack_from("<I", raw, 12)[0]
        raw = raw[20:20 + length]
    try:
        return json.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError):
        return {}


def companions(path, doc):
    out = []
    for kind in ("buffers", "images"):
        for item in doc.get(kind, []) if isinstance(doc.get(kind), list) else []:
            uri = item.get("uri") if isinstance(item, dict) else None
            if not isinstance(uri, str) or uri.startswith("data:"):
                continue
            name = urllib.parse.unquote(uri)
            if "/" in name or not os.path.isfile(os.path.join(os.path.dirname(path), name)):
                continue
            data = PNG if kind == "images" else open(os.path.join(os.path.dirname(path), name), "rb").read()
            out.append((name, data))
    return out


def pack(path):
    raw = open(path, "rb").read()
    seed = bytes([1 if path.endswith(".glb") else 0]) + struct.pack("<I", len(raw)) + raw
    for name, data in companions(path, document(raw)):
        encoded = name.encode()
        if 0 < len(encoded) < 256:
            seed += bytes([len(encoded)]) + encoded + struct.pack("<I", len(data)) + data
    return seed


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for k, path in enumerate(sys.argv[2:]):
        seed = pack(path)
        if len(seed) <= 262144:
            with open(os.path.join(out, "seed_%03d" % k), "wb") as f:
                f.write(seed)


if __name__ == "__main__":
    main()
