"""The JSON schema of ``verification.json`` (``report.schema.json``) and a validator for it.

The validator implements the part of JSON Schema the file uses (``type``, ``enum``,
``required``, ``properties``, ``additionalProperties``, ``items``, ``minimum``,
``pattern``, local ``$ref``) so that reading a report needs no extra dependency; the
test suite also validates with the ``jsonschema`` package.
"""

from __future__ import annotations

import json
import re
from functools import lru_cache
from pathlib import Path

from iik.files import read_text

__all__ = ["SCHEMA_PATH", "schema", "schema_errors"]

#: The schema file shipped with the package.
SCHEMA_PATH = Path(__file__).with_name("report.schema.json")

_TYPES = {
    "object": lambda v: isinstance(v, dict),
    "array": lambda v: isinstance(v, list),
    "string": lambda v: isinstance(v, str),
    "boolean": lambda v: isinstance(v, bool),
    "integer": lambda v: isinstance(v, int) and not isinstance(v, bool),
    "number": lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
    "null": lambda v: v is None,
}


@lru_cache(maxsize=1)
def schema() -> dict:
    """The report schema (parsed once)."""
    return json.loads(read_text(SCHEMA_PATH, "SCHEMA_PATH", limit=1_000_000, what="the report schema"))


def _resolve(node: dict, root: dict) -> dict:
    while "$ref" in node:
        path = node["$ref"].removeprefix("#/").split("/")
        node = root
        for part in path:
            node = node[part]
    return node


def _check(value, node: dict, root: dict, where: str, out: list[str]) -> None:
    node = _resolve(node, root)
    types = node.get("type")
    if types is not None:
        types = [types] if isinstance(types, str) else types
        if not any(_TYPES[t](value) for t in types):
            out.append(f"{where}: expected {' or '.join(types)}, got {type(value).__name__}")
            return
    if "enum" in node and value not in node["enum"]:
        out.append(f"{where}: {value!r} is not one of {node['enum']}")
    if "minimum" in node and isinstance(value, (int, float)) and value < node["minimum"]:
        out.append(f"{where}: {value} < minimum {node['minimum']}")
    if "pattern" in node and isinstance(value, str) and not re.search(node["pattern"], value):
        out.append(f"{where}: {value!r} does not match {node['pattern']}")
    if isinstance(value, dict):
        props = node.get("properties", {})
        for key in node.get("required", ()):
            if key not in value:
                out.append(f"{where}: missing required {key!r}")
        extra = node.get("additionalProperties", True)
        for key, v in value.items():
            if key in props:
                _check(v, props[key], root, f"{where}.{key}", out)
            elif extra is False:
                out.append(f"{where}: unexpected property {key!r}")
            elif isinstance(extra, dict):
                _check(v, extra, root, f"{where}.{key}", out)
    if isinstance(value, list) and "items" in node:
        for i, v in enumerate(value):
            _check(v, node["items"], root, f"{where}[{i}]", out)


def schema_errors(document) -> list[str]:
    """Every way ``document`` breaks the report schema (empty if it conforms)."""
    out: list[str] = []
    root = schema()
    _check(document, root, root, "$", out)
    return out
