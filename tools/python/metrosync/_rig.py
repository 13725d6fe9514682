"""Rigs: a YAML file's path or a dict, with overrides; and the errors about them in Python terms."""

import json
import os
import re

from . import _metrosync as _core

RigError = _core.RigError  # a bad rig, override or option (a ValueError)
RigError.__module__ = "metrosync"  # tracebacks say metrosync.RigError, not the C++ module's name
RigError.__doc__ = """A rig, an override or an option that metrosync refuses (a ValueError).

Raised before anything runs or is written, as the command line exits with code 2. The message
names what is wrong where the caller wrote it: a file's line and column, a dict's key
(``rig['metronomes'][0]['pendulum']['mass'] = -0.02: must be > 0``), an override
(``overrides['platform.friction.mu'] = -1: must be >= 0``) or an argument (``jobs=0: ...``).
A failed simulation is :class:`SimulationError` instead.
"""

# What stands for a dict rig in the loader's messages (and names it when it has no `name` key).
_DICT_NAME = "rig"


def _json_default(value):
    """numpy scalars and arrays (and anything with .tolist()/.item()) as plain Python values."""
    for convert in ("tolist", "item"):
        if hasattr(value, convert):
            return getattr(value, convert)()
    raise TypeError("%s is not a rig value (numbers, strings, lists, dicts)" % type(value).__name__)


def _value_text(value):
    """A value as an override's text (parsed as YAML): JSON for everything but a string."""
    if isinstance(value, str):
        return value
    return json.dumps(value, default=_json_default)


def _subscripts(data, dotted):
    """The dotted key path `metronomes.0.pendulum.mass` as the dict's subscripts
    `['metronomes'][0]['pendulum']['mass']`, and the value there (None when absent)."""
    node, out, found = data, "", data is not None
    for segment in dotted.split("."):
        index = int(segment) if re.fullmatch(r"\d+", segment) else None
        if found and isinstance(node, list) and index is not None and index < len(node):
            node = node[index]
        elif found and isinstance(node, dict) and segment in node:
            node = node[segment]
        else:
            found = False
        out += "[%d]" % index if index is not None else "[%r]" % segment
    return out, (node if found else None), found


def _short_repr(value):
    text = repr(value)
    return text if len(text) <= 60 else "<%s of %d>" % (type(value).__name__, len(value))


def _dict_message(data, rest):
    """`metronomes.0.pendulum.mass = -0.02: must be > 0` about a dict as
    `rig['metronomes'][0]['pendulum']['mass'] = -0.02: must be > 0`."""
    m = re.match(r"([A-Za-z0-9_.*-]+)(?: = (.*?))?: (.*)", rest, re.S)
    if not m:
        return _DICT_NAME + ": " + rest
    subscripts, value, found = _subscripts(data, m.group(1))
    shown = " = " + _short_repr(value) if found and m.group(2) is not None else (
        "" if m.group(2) is None else " = " + m.group(2))
    return "%s%s%s: %s" % (_DICT_NAME, subscripts, shown, m.group(3))


class _Origin:
    """Where an override came from, to say so in messages: `overrides['k'] = v` or `duration=30`."""

    def __init__(self, key, value, label):
        self.key, self.value, self.label = key, value, label
        self.text = "%s=%s" % (key, _value_text(value))


def _override_message(message, origins):
    """The loader's `--set KEY=VALUE: KEY = VALUE: what` as `overrides['KEY'] = VALUE: what`."""
    for o in origins:
        at = message.find("--set " + o.text)
        if at < 0:
            continue
        tail = message[at + len("--set ") + len(o.text):]
        # the loader repeats the key and value after the override: said once is enough
        tail = re.sub(r"^: %s(?: = [^:]*)?: " % re.escape(o.key), ": ", tail, count=1)
        return message[:at] + o.label + tail
    return message


def _number(text):
    """A number the C++ side printed in full (-0.29999999999999999) as Python prints it (-0.3)."""
    try:
        value = float(text)
    except ValueError:
        return text
    return text if re.fullmatch(r"-?\d+", text) else repr(value)


# The command line's ways of naming a key's value in a message, and Python's: (pattern with the
# key and the value, the form of (key, value)). The loader's "KEY = VALUE: " that follows says it
# again and is dropped.
_KEY_WORDS = [(r"--vary point ([^=\s]+)=([^:\s]+)", "vary[%r] at %s"),
              (r"the drawn ([^=\s]+)=([^:\s]+)", "random[%r] drew %s"),
              (r"--param ([^=\s]+)=([^:\s]+)", "param=%r at %s"),
              (r"--random ([^=\s]+)=(\S+?:\S+?)(?=: )", "random[%r] = (%s)"),
              (r"--vary ([^=\s]+)=(\S+?)(?=: )", "vary[%r] = %r"),
              (r"--(param|fold|free) ([^=\s:]+)(?=: )", "%s=%r")]


def _key_words(message):
    for pattern, form in _KEY_WORDS:
        m = re.search(pattern, message)
        if not m:
            continue
        if form.startswith("%s="):  # --param KEY: the option's name, then the key
            said, key = form % (m.group(1), m.group(2)), m.group(2)
        else:
            key, value = m.group(1), m.group(2)
            shown = value if form.endswith("%r") else ", ".join(
                _number(v) for v in value.split(":"))
            said = form % (key, shown)
        repeat = r"^: %s(?: = [^:\n]*)?(?=: )" % re.escape(key)
        rest = re.sub(repeat, "", message[m.end():], count=1)
        message = message[:m.start()] + said + rest
    return message


def _python_words(message):
    """The command line's words in a message as Python's: ``--vary point K=V`` as
    ``vary['K'] at V``, ``--engine x`` as ``engine='x'``, a number printed in full as Python
    prints it."""
    message = re.sub(r"-?\d+\.\d{15,}(?:e[+-]?\d+)?", lambda m: _number(m.group(0)), message)
    message = _key_words(message)

    def option(m):
        name = {"from": "from_", "max-points": "max_points"}.get(m.group(1), m.group(1))
        value = m.group(2)
        number = re.fullmatch(r"-?[\d.]+(?:e[+-]?\d+)?", value)
        placeholder = value.isupper()  # the usage's own words: --from VALUE
        shown = _number(value) if number else value if placeholder else repr(value)
        return "%s=%s" % (name.replace("-", "_"), shown)
    return re.sub(r"--([a-z][a-z0-9-]*)[ =]([^\s:,()`']+)", option, message)


class Rig:
    """A rig: a YAML file (its path) or a dict in the YAML's structure, and overrides {KEY: value}
    applied in order as the command line's ``--set KEY=VALUE`` (keys as in docs/README's key
    language: ``platform.friction.mu``, ``metronomes.1.start.angle``, ``metronomes.*.nu``).
    Made by :func:`load_rig`, which checks it.

    >>> rig = metrosync.load_rig("yaml/rigs/experiment.yaml", {"platform.friction.mu": 0.3})
    >>> rig.scaled()["mu"] > 0
    True
    """

    def __init__(self, path=None, data=None, overrides=None):
        self.path = path  # the file, or None for a dict
        self._data = data
        self._text = None if data is None else json.dumps(data, default=_json_default)
        self.overrides = dict(overrides or {})
        self._scaled = None
        self._network = None

    @property
    def name(self):
        """The rig's name (its `name` key, else the file's stem, else 'rig')."""
        return self.to_dict().get("name", _DICT_NAME)

    def _origins(self, extra=()):
        origins = [_Origin(k, v, "overrides[%r] = %s" % (k, _short_repr(v)))
                   for k, v in self.overrides.items()]
        return origins + list(extra)

    def _source(self, extra=()):
        """The C++ side's rig: the text (None: read the file), its name in messages, the sets."""
        sets = [o.text for o in self._origins(extra)]
        return _core.RigSource(self._text, self.path if self.path is not None else _DICT_NAME,
                               sets)

    def _explain(self, error, extra=()):
        """A RigError from the C++ side, said in Python terms."""
        message = _override_message(str(error), self._origins(extra))
        if self.path is None:  # a dict: its subscripts, not a file's line and column
            m = re.match(r"%s:\d+:\d+: (.*)" % re.escape(_DICT_NAME), message, re.S)
            if m:
                message = _dict_message(self._data, m.group(1))
            elif message.startswith(_DICT_NAME + ": "):
                message = message[len(_DICT_NAME) + 2:]
        return RigError(_python_words(message))

    def _call(self, function, *args, extra=(), **kwargs):
        """function(self._source(extra), ...), its RigError said in Python terms."""
        try:
            return function(self._source(extra), *args, **kwargs)
        except RigError as e:
            raise self._explain(e, extra) from None

    def scaled(self):
        """The scaled parameters (epsilon, mu, c, nu, J, theta_c, alpha, ...): the object
        ``metrosync scale --json`` prints, as a dict.

        >>> metrosync.load_rig("yaml/rigs/paper/f4.1.yaml").scaled()["mu"]
        0.0
        """
        if self._scaled is None:
            self._scaled = json.loads(self._call(_core.scaled_json))
        return self._scaled

    def to_dict(self):
        """The rig after its overrides as a dict (what summary.json calls resolved_rig): a rig
        again for :func:`load_rig`.

        >>> d = metrosync.load_rig("yaml/rigs/experiment.yaml").to_dict()
        >>> d["platform"]["friction"]["mu"]
        0.00065
        """
        return json.loads(self._call(_core.resolved_json))

    def _is_network(self):
        """A network of several platforms (docs/networks.md)? Loads it: a bad one raises."""
        if self._network is None:
            self._network = self._call(_core.is_network)
        return self._network

    def _check(self):
        """Loads the rig as the commands will: a bad rig raises RigError here."""
        if not self._is_network():
            self.scaled()

    def __repr__(self):
        source = self.path if self.path is not None else "<dict>"
        more = " + %d overrides" % len(self.overrides) if self.overrides else ""
        if self._is_network():
            return "Rig(%s%s: a network of platforms)" % (source, more)
        s = self.scaled()
        keys = [k for k in ("epsilon", "mu", "c", "nu", "J", "theta_c", "alpha") if k in s]
        body = ", ".join("%s=%s" % (k, s[k]) for k in keys)
        return "Rig(%s%s: %s)" % (source, more, body)


def load_rig(rig, overrides=None):
    """A :class:`Rig` from a YAML file's path, a dict (the YAML's structure) or another Rig (its
    overrides first, then these), checked at once: a bad rig raises :class:`RigError` naming the
    file's line or the dict's key (``rig['metronomes'][0]['pendulum']['mass'] = -0.02: must be >
    0``) or the override (``overrides['platform.friction.mu'] = -1: must be >= 0``).

    >>> rig = metrosync.load_rig({"units": "scaled", "epsilon": 0.05, ...})
    >>> rig = metrosync.load_rig("yaml/rigs/experiment.yaml", {"metronomes.*.start.rate": 0.1})
    """
    if isinstance(rig, Rig):
        made = Rig(rig.path, rig._data, {**rig.overrides, **dict(overrides or {})})
    elif isinstance(rig, dict):
        made = Rig(data=rig, overrides=overrides)
    elif isinstance(rig, (str, bytes, os.PathLike)):
        made = Rig(path=os.fsdecode(rig), overrides=overrides)
    else:
        raise TypeError("a rig is a Rig, a dict or a YAML file's path, not %s" % type(rig).__name__)
    made._check()
    return made


def as_rig(rig):
    """A Rig as given, else load_rig(rig): what every call takes."""
    return rig if isinstance(rig, Rig) else load_rig(rig)
