"""Python values as TOML text: the overrides of load_scene and the scenes built from dicts."""

import math


def value_text(value):
    """One TOML value: bool, number, string, list or (inline) table."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)  # the shortest text that reads back as the same double
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{key} = {value_text(item)}" for key, item in value.items()) + " }"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(value_text(item) for item in value) + "]"
    if hasattr(value, "tolist"):  # numpy scalars and arrays
        return value_text(value.tolist())
    raise TypeError(f"cannot write {type(value).__name__} {value!r} as a TOML value")


def override_text(value):
    """An override's value as `--set` takes it: strings as they are, the rest as TOML."""
    return value if isinstance(value, str) else value_text(value)


def document_text(tables):
    """A scene document: {"time": {...}, "material": [{...}, ...], ...} as TOML."""
    lines = []
    for name, content in tables.items():
        if isinstance(content, dict):
            lines.append(f"[{name}]")
            lines += [f"{key} = {value_text(item)}" for key, item in content.items()]
        elif isinstance(content, (list, tuple)) and all(isinstance(item, dict) for item in content):
            for item in content:
                lines.append(f"[[{name}]]")
                lines += [f"{key} = {value_text(entry)}" for key, entry in item.items()]
        else:
            raise TypeError(f"scene section '{name}' must be a dict or a list of dicts")
        lines.append("")
    return "\n".join(lines)
