"""Python values to the text a CLI flag would receive, so the core reads them as the CLI does.

Numbers become their shortest exact text (0.84 -> "0.84"), sequences "36x36" for sizes and
"0,90" for lists, strings pass unchanged ("840um", "A4 landscape"); anything else is a
TypeError naming the parameter.
"""

import math
import numbers
import os

_SEPARATOR = {"size": "x", "number list": ","}


def _scalar_text(where, value):
    if isinstance(value, bool) or value is None:
        raise TypeError(f"{where}: expected a number or text with a unit, got {value!r}")
    if isinstance(value, str):
        return value
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        v = float(value)
        # The CLI refuses "nan" and "inf" with its own message; repr() is the shortest text
        # that reads back as the same double.
        return ("nan" if math.isnan(v) else "inf" if math.isinf(v) else repr(v))
    raise TypeError(f"{where}: expected a number or text with a unit, got {type(value).__name__}")


def value_text(where, param, value):
    """The CLI text of `value` for the table entry `param` (a dict of strand.generators())."""
    if isinstance(value, str):
        return value
    if param["type"] == "switch" and isinstance(value, bool):
        return "true" if value else "false"
    separator = _SEPARATOR.get(param["type"])
    if separator is not None and not isinstance(value, (str, bytes, dict)) and hasattr(value, "__iter__"):
        return separator.join(_scalar_text(where, v) for v in value)
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return _scalar_text(where, value)


def flag_key(name):
    """Python keyword -> table key: layer_height -> layer-height."""
    return name.replace("_", "-")


def py_name(key):
    """Table key or generator name -> Python identifier: missing-rib -> missing_rib."""
    return key.replace("-", "_")


def param_texts(function, table_name, params, given):
    """{table key: text} of the keywords `given`; TypeError for an unknown one."""
    by_key = {p["key"]: p for p in params}
    texts = {}
    for name, value in given.items():
        key = flag_key(name)
        if key not in by_key:
            known = ", ".join(py_name(p["key"]) for p in params)
            raise TypeError(f"{function}() got an unexpected keyword argument '{name}' (parameters: {known})")
        if value is None:  # the default, as when the flag is not given
            continue
        texts[key] = value_text(f"{table_name}.{key}", by_key[key], value)
    return texts


def path_text(where, value):
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    raise TypeError(f"{where}: expected a file path (str or os.PathLike), got {type(value).__name__}")


def doc_for(title, summary, params, common):
    """A docstring listing every parameter with its unit, default and allowed range."""
    lines = [title, "", summary, "",
             "Keyword parameters (a number in the unit shown, or text with any unit of the same",
             "kind, as the CLI flag takes it: nozzle=\"840um\"):", ""]
    width = max([len(py_name(p["key"])) for p in params] + [12])
    for p in params:
        unit = f" [{p['unit']}]" if p["unit"] else ""
        default = p["default"] if p["default"] is not None else (p["default_text"] or None)
        extra = []
        if default is not None and default != "":
            extra.append(f"default {default}")
        if p["rule"]:
            extra.append(p["rule"])
        if p["choices"]:
            extra.append("one of " + ", ".join(p["choices"]))
        tail = f" ({'; '.join(extra)})" if extra else ""
        lines.append(f"  {py_name(p['key']):<{width}}  {p['help']}{unit}{tail}")
    lines += [""] + common
    return "\n".join(lines)
