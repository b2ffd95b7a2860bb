# ruff: noqa: UP031  (rosbag's own %-formats, kept so the output matches to the character)
"""What `rosbag info` prints, text or YAML, from a bag's index (no message is read).

The layout is rosbag 1.15's to the character: a label column as wide as the longest label
plus one, durations as `%.1fs`/`M:SSs (Ns)`/`Hhr M:SSs (Ns)`, local times with two decimals,
1024-based sizes, topics sorted with counts right-aligned and `msgs`/`msg `, and the
compression lines rosbag adds for compressed chunks.
"""

from __future__ import annotations

import datetime

from kame.bag.records import ChunkHeader, ChunkInfo, Connection

__all__ = ["BagSummary", "human_readable_size", "info_text", "info_yaml", "yaml_key"]


class BagSummary:
    # A plain class, as the record types: `rosbag info` must not pay for importing dataclasses.
    __slots__ = ("chunk_headers", "chunk_infos", "connections", "frequencies", "path", "size", "version")

    def __init__(self, path: str, size: int, connections: dict[int, Connection], chunk_infos: list[ChunkInfo],
                 chunk_headers: list[ChunkHeader], frequencies: dict[str, float] | None = None,
                 version: str = "2.0") -> None:
        self.version = version  # "mcap" for an MCAP file (kame.bag.mcap_file)
        self.path = path
        self.size = size
        self.connections = connections
        self.chunk_infos = chunk_infos
        self.chunk_headers = chunk_headers
        self.frequencies = frequencies  # topic -> median rate (--freq)


def human_readable_size(size: float) -> str:
    for suffix in ("KB", "MB", "GB", "TB", "PB", "EB", "ZB", "YB"):
        size /= 1024.0
        if size < 1024.0:
            return f"{size:.1f} {suffix}"
    return "-"


def human_readable_frequency(freq: float) -> str:
    for suffix in ("Hz", "kHz", "MHz", "GHz", "THz", "PHz", "EHz", "ZHz", "YHz"):
        if freq < 1000.0:
            return f"{freq:.1f} {suffix}"
        freq /= 1000.0
    return "-"


def _time_to_str(secs: float) -> str:
    frac = ("%.2f" % (secs - int(secs)))[1:]
    return datetime.datetime.fromtimestamp(secs).strftime("%b %d %Y %H:%M:%S") + frac


def _to_sec(t: tuple[int, int]) -> float:
    return float(t[0]) + float(t[1]) / 1e9


def _duration_str(duration: float) -> str:
    dur_secs = duration % 60
    dur_mins = int(duration / 60)
    dur_hrs = int(dur_mins / 60)
    if dur_hrs > 0:
        return "%dhr %d:%02ds (%ds)" % (dur_hrs, dur_mins % 60, dur_secs, duration)
    if dur_mins > 0:
        return "%d:%02ds (%ds)" % (dur_mins, dur_secs, duration)
    return "%.1fs" % duration


class _Topics:
    __slots__ = ("conn_counts", "datatype_infos", "datatypes", "msg_counts", "topics")

    def __init__(self, datatype_infos: list[tuple[str, str]], topics: list[str], datatypes: dict[str, str],
                 conn_counts: dict[str, int], msg_counts: dict[str, int]) -> None:
        self.datatype_infos = datatype_infos
        self.topics = topics
        self.datatypes = datatypes
        self.conn_counts = conn_counts
        self.msg_counts = msg_counts


def _topics(s: BagSummary) -> _Topics:
    seen: set[str] = set()
    infos: list[tuple[str, str]] = []
    for conn in s.connections.values():
        if conn.datatype not in seen:
            seen.add(conn.datatype)
            infos.append((conn.datatype, conn.md5sum))
    per_conn: dict[int, int] = {}
    for chunk in s.chunk_infos:
        for conn_id, count in chunk.counts.items():
            per_conn[conn_id] = per_conn.get(conn_id, 0) + count
    datatypes: dict[str, str] = {}
    conn_counts: dict[str, int] = {}
    msg_counts: dict[str, int] = {}
    for conn in s.connections.values():
        datatypes.setdefault(conn.topic, conn.datatype)
        conn_counts[conn.topic] = conn_counts.get(conn.topic, 0) + 1
        msg_counts[conn.topic] = msg_counts.get(conn.topic, 0) + per_conn.get(conn.id, 0)
    return _Topics(sorted(infos), sorted(datatypes), datatypes, conn_counts, msg_counts)


def _compression(s: BagSummary) -> tuple[dict[str, int], dict[str, int], dict[str, int]]:
    counts: dict[str, int] = {}
    uncompressed: dict[str, int] = {}
    compressed: dict[str, int] = {}
    for h in s.chunk_headers:
        counts[h.compression] = counts.get(h.compression, 0) + 1
        uncompressed[h.compression] = uncompressed.get(h.compression, 0) + h.uncompressed_size
        compressed[h.compression] = compressed.get(h.compression, 0) + h.compressed_size
    return counts, uncompressed, compressed


def _span(s: BagSummary) -> tuple[float, float]:
    return _to_sec(s.chunk_infos[0].start), _to_sec(s.chunk_infos[-1].end)


def info_text(s: BagSummary) -> str:
    rows: list[tuple[str, str]] = [("path", s.path), ("version", s.version)]
    if not s.chunk_infos:
        rows.append(("size", human_readable_size(s.size)))
    else:
        start, end = _span(s)
        duration = end - start
        rows.append(("duration", _duration_str(duration)))
        rows.append(("start", f"{_time_to_str(start)} ({start:.2f})"))
        rows.append(("end", f"{_time_to_str(end)} ({end:.2f})"))
        rows.append(("size", human_readable_size(s.size)))
        rows.append(("messages", str(sum(c.message_count for c in s.chunk_infos))))
        counts, unc, comp = _compression(s)
        if not counts:
            rows.append(("compression", "none"))
        else:
            total = len(s.chunk_headers)
            parts = []
            for count, kind in sorted(((v, k) for k, v in counts.items()), reverse=True):
                if kind != "none":
                    parts.append("%s [%d/%d chunks; %.2f%%]" % (kind, count, total, 100.0 * comp[kind] / unc[kind]))
                else:
                    parts.append("%s [%d/%d chunks]" % (kind, count, total))
            rows.append(("compression", ", ".join(parts)))
            if any(k != "none" for k in counts):
                total_unc = sum(unc.values())
                total_comp = sum(comp.values())
                unc_str = human_readable_size(total_unc)
                comp_str = human_readable_size(total_comp)
                width = max(len(unc_str), len(comp_str))
                if duration > 0:
                    unc_rate = human_readable_size(total_unc / duration)
                    comp_rate = human_readable_size(total_comp / duration)
                    rate_width = max(len(unc_rate), len(comp_rate))
                    rows.append(("uncompressed", "%*s @ %*s/s" % (width, unc_str, rate_width, unc_rate)))
                    rows.append(("compressed", "%*s @ %*s/s (%.2f%%)" % (width, comp_str, rate_width, comp_rate,
                                                                        100.0 * total_comp / total_unc)))
                else:
                    rows.append(("uncompressed", "%*s" % (width, unc_str)))
                    rows.append(("compressed", "%*s" % (width, comp_str)))
        t = _topics(s)
        freqs = s.frequencies or {}
        if t.topics:
            max_topic = max(len(x) for x in t.topics)
            max_type = max(len(x) for x, _ in t.datatype_infos)
            max_count = max(len("%d" % n) for n in t.msg_counts.values())
            max_freq = max((len(human_readable_frequency(f)) for f in freqs.values()), default=0)
            for i, (datatype, md5) in enumerate(t.datatype_infos):
                rows.append(("types" if i == 0 else "", "%-*s [%s]" % (max_type, datatype, md5)))
            for i, topic in enumerate(t.topics):
                n = t.msg_counts[topic]
                line = "%-*s   %*d %s" % (max_topic, topic, max_count, n, "msgs" if n > 1 else "msg ")
                if topic in freqs:
                    line += " @ %*s" % (max_freq, human_readable_frequency(freqs[topic]))
                else:
                    line += "   %*s" % (max_freq, "")
                line += " : %-*s" % (max_type, t.datatypes[topic])
                if t.conn_counts[topic] > 1:
                    line += " (%d connections)" % t.conn_counts[topic]
                rows.append(("topics" if i == 0 else "", line))
    width = max(len(label) for label, _ in rows) + 1
    out = "".join("%-*s %s\n" % (width, label + ":" if label else "", value) for label, value in rows)
    return out.rstrip()


def info_yaml(s: BagSummary) -> str:
    out = f"path: {s.path}\nversion: {s.version}\n"
    if not s.chunk_infos:
        return out + f"size: {s.size}\nindexed: False\n"
    start, end = _span(s)
    out += "duration: %.6f\nstart: %.6f\nend: %.6f\nsize: %d\n" % (end - start, start, end, s.size)
    out += "messages: %d\nindexed: True\n" % sum(c.message_count for c in s.chunk_infos)
    counts, unc, comp = _compression(s)
    if not counts:
        out += "compression: none\n"
    else:
        _, main = sorted(((v, k) for k, v in counts.items()), reverse=True)[0]
        out += f"compression: {main}\n"
        if any(k != "none" for k in counts):
            out += "uncompressed: %d\ncompressed: %d\n" % (sum(unc.values()), sum(comp.values()))
    t = _topics(s)
    out += "types:\n"
    for datatype, md5 in t.datatype_infos:
        out += f"    - type: {datatype}\n      md5: {md5}\n"
    out += "topics:\n"
    freqs = s.frequencies or {}
    for topic in t.topics:
        out += f"    - topic: {topic}\n      type: {t.datatypes[topic]}\n      messages: {t.msg_counts[topic]}\n"
        if t.conn_counts[topic] > 1:
            out += f"      connections: {t.conn_counts[topic]}\n"
        if topic in freqs:
            out += "      frequency: %.4f\n" % freqs[topic]
    return out


class _Obj:
    def __init__(self, d: dict[str, object]) -> None:
        for k, v in d.items():
            if isinstance(v, (list, tuple)):
                setattr(self, k, [_Obj(x) if isinstance(x, dict) else x for x in v])
            else:
                setattr(self, k, _Obj(v) if isinstance(v, dict) else v)


def _print_yaml(val: object, indent: int = 0) -> str:
    pad = "  " * indent
    if isinstance(val, list):
        return "".join(f"{pad}- {_print_yaml(item, indent + 1)}\n" for item in val)
    if isinstance(val, _Obj):
        items = list(vars(val).items())
        parts = []
        for i, (k, v) in enumerate(items):
            parts.append((pad if i else "") + f"{k}: {v}" + ("\n" if i < len(items) - 1 else ""))
        return "".join(parts)
    return pad + str(val)


def yaml_key(text: str, key: str) -> str | None:
    """What `rosbag info -y -k KEY` prints (rosbag evaluates `obj.KEY` on the YAML), or None."""
    from typing import Any

    import yaml

    obj = _Obj(yaml.safe_load(text))
    value: Any = obj
    try:
        for part in key.split("."):
            name, _, index = part.partition("[")
            value = getattr(value, name)
            if index:
                value = value[int(index.rstrip("]"))]
    except (AttributeError, IndexError, ValueError, TypeError):
        return None
    return _print_yaml(value)
