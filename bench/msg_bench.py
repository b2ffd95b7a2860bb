#!/usr/bin/env python3
"""Message serialization benchmark: kame's generated classes vs genpy's, and memcpy.

    bench/msg_bench.sh [--reps 3] [--block 0.05] [--blocks 5] [--no-kame-on-debian-python] [--json FILE]

One file, two roles.  The driver (no --worker) runs this same file as a worker under
each implementation's interpreter, repetitions interleaved (kame, genpy, kame, ...),
each worker a fresh process printing one JSON line, and prints one table of medians:

- kame:  the checkout's .venv/bin/python, where `from std_msgs.msg import String`
         resolves to kame's generated classes;
- genpy: Debian's /usr/bin/python3 with python3-genpy and the Debian message packages;
- kame@deb: kame's classes (PYTHONPATH=src) under Debian's /usr/bin/python3, the same
         interpreter as genpy: the venv's interpreter is a different build (pyenv 3.11.7,
         libpython shared) and is slower on the same code, see the table's interpreter check.

A worker builds the same message contents on both sides (the driver checks that the
serialized bytes are identical) and times, per message, the way a node uses messages:
  serialize    msg.serialize(buff) into a fresh io.BytesIO, then buff.getvalue()
  ser. reused  msg.serialize(buff) into one BytesIO reused (seek(0), truncate())
  deserialize  Cls().deserialize(data) from bytes
  node: to frame    what a publisher does with a message: rospy's serialize_message()
               into its reused BytesIO (length prefix, header seq) and getvalue(); kame's
               kame.node.topics.serialize_frame(msg)
  node: from frame  what a subscriber does with a frame's payload: rospy's
               Cls().deserialize(payload bytes); kame's Cls._from_buffer(memoryview)
and, for the small messages, two parts of those loops that are not the codec's own work:
  Cls() alone        the constructor "deserialize" runs first (its defaults are overwritten)
  floor: BytesIO     the "serialize" loop with msg.serialize(b) replaced by b.write(bytes):
               BytesIO(), one write of the same bytes, getvalue(); the same code on every side
and a plain copy of the large messages' bytes (bytearray(b), a memoryview slice
assignment into a preallocated buffer, numpy.copyto when numpy imports) as the physical
reference.  Standard library only (numpy optional).  Every worker is started in its own
process group and stopped by that group's id, never by name.
"""

from __future__ import annotations

import argparse
import gc
import hashlib
import io
import json
import os
import shlex
import shutil
import signal
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
IMPLS = {  # name -> command prefix of the interpreter that runs the worker
    'kame': [os.path.join(ROOT, '.venv', 'bin', 'python')],
    'genpy': ['/usr/bin/python3'],
}
MISSING_EXIT = 3
clock = time.perf_counter
CLOCKS = {'wall': time.perf_counter, 'cpu': time.process_time}
rate_clock = clock  # what rate() times with; the worker sets it from --clock

# name, label; the order of the table
MESSAGES = [
    ('string', 'std_msgs/String'),
    ('twist', 'geometry_msgs/Twist'),
    ('pose', 'geometry_msgs/Pose'),
    ('joints', 'sensor_msgs/JointState 6 joints'),
    ('odometry', 'nav_msgs/Odometry'),
    ('image', 'sensor_msgs/Image 1920x1080 rgb8'),
    ('cloud', 'sensor_msgs/PointCloud2 1M pts'),
]
LARGE = ('image', 'cloud')
OPS = [('ser', 'serialize'), ('ser_reuse', 'ser. reused buf'), ('deser', 'deserialize'),
       ('send', 'node: to frame'), ('recv', 'node: from frame'), ('construct', 'Cls() alone'),
       ('ser_floor', 'floor: BytesIO')]
NODE_OPS = ('send', 'recv')
SMALL_ONLY = (*NODE_OPS, 'construct', 'ser_floor')  # not measured for the large messages
COPIES = [('bytearray', 'bytearray(b)'), ('mv_assign', 'dst[:] = b'), ('numpy', 'numpy.copyto')]


# ====================================================================== worker
def pattern(size: int) -> bytes:
    """size bytes that are not all zero (identical in every process)."""
    return (bytes(range(256)) * (size // 256 + 1))[:size]


def set_header(h, frame_id):
    h.seq = 42
    h.stamp.secs = 1700000000
    h.stamp.nsecs = 123456789
    h.frame_id = frame_id


def build_messages():
    """{name: (class, message)} with identical contents for kame and genpy."""
    from geometry_msgs.msg import Pose, Twist
    from nav_msgs.msg import Odometry
    from sensor_msgs.msg import Image, JointState, PointCloud2, PointField
    from std_msgs.msg import String

    out = {'string': (String, String(data='hello kame'))}

    tw = Twist()
    tw.linear.x, tw.linear.y, tw.linear.z = 0.5, -0.25, 0.0
    tw.angular.x, tw.angular.y, tw.angular.z = 0.0, 0.0, 1.5
    out['twist'] = (Twist, tw)

    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = 1.0, 2.0, 0.5
    pose.orientation.z, pose.orientation.w = 0.3826834, 0.9238795
    out['pose'] = (Pose, pose)

    js = JointState()
    set_header(js.header, 'base_link')
    js.name = ['shoulder_pan', 'shoulder_lift', 'elbow', 'wrist_1', 'wrist_2', 'wrist_3']
    js.position = [0.1 * i for i in range(6)]
    js.velocity = [0.01 * i for i in range(6)]
    js.effort = [1.5 * i for i in range(6)]
    out['joints'] = (JointState, js)

    od = Odometry()
    set_header(od.header, 'odom')
    od.child_frame_id = 'base_link'
    p = od.pose.pose
    p.position.x, p.position.y, p.position.z = 1.0, 2.0, 0.0
    p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w = 0.0, 0.0, 0.3826834, 0.9238795
    od.pose.covariance = [0.01 * i for i in range(36)]
    t = od.twist.twist
    t.linear.x, t.linear.y, t.linear.z = 0.5, 0.0, 0.0
    t.angular.x, t.angular.y, t.angular.z = 0.0, 0.0, 0.1
    od.twist.covariance = [0.001 * i for i in range(36)]
    out['odometry'] = (Odometry, od)

    img = Image()
    set_header(img.header, 'camera')
    img.height, img.width, img.encoding, img.is_bigendian, img.step = 1080, 1920, 'rgb8', 0, 1920 * 3
    img.data = pattern(1920 * 1080 * 3)
    out['image'] = (Image, img)

    pc = PointCloud2()
    set_header(pc.header, 'lidar')
    pc.height, pc.width = 1, 1_000_000
    pc.fields = [PointField(name=n, offset=4 * i, datatype=PointField.FLOAT32, count=1)
                 for i, n in enumerate(('x', 'y', 'z', 'intensity'))]
    pc.is_bigendian, pc.point_step, pc.row_step, pc.is_dense = False, 16, 16 * 1_000_000, True
    pc.data = pattern(16 * 1_000_000)
    out['cloud'] = (PointCloud2, pc)
    return out


def node_ops(impl, cls, msg, data):
    """The node's own paths: (send, recv) functions(n), see the module's docstring."""
    if impl == 'genpy':
        from rospy.msg import serialize_message

        buff = io.BytesIO()

        def send(n):
            b = buff
            for seq in range(n):
                serialize_message(b, seq, msg)
                b.getvalue()
                b.seek(0)
                b.truncate(0)

        def recv(n):
            for _ in range(n):
                cls().deserialize(data)

        return send, recv
    from kame.node.topics import serialize_frame

    view = memoryview(data)
    from_buffer = cls._from_buffer

    def send(n):
        for _ in range(n):
            serialize_frame(msg)

    def recv(n):
        for _ in range(n):
            from_buffer(view)

    return send, recv


def loops(impl, cls, msg, data):
    """op -> function(n) running the op n times (the loop inlined, as a node would run it)."""
    BytesIO = io.BytesIO

    def ser(n):
        for _ in range(n):
            b = BytesIO()
            msg.serialize(b)
            b.getvalue()

    reused = BytesIO()

    def ser_reuse(n):
        b = reused
        for _ in range(n):
            b.seek(0)
            b.truncate()
            msg.serialize(b)

    def deser(n):
        for _ in range(n):
            cls().deserialize(data)

    def construct(n):
        for _ in range(n):
            cls()

    def ser_floor(n):
        for _ in range(n):
            b = BytesIO()
            b.write(data)
            b.getvalue()

    send, recv = node_ops(impl, cls, msg, data)
    return {'ser': ser, 'ser_reuse': ser_reuse, 'deser': deser, 'send': send, 'recv': recv,
            'construct': construct, 'ser_floor': ser_floor}


def copies(data):
    """name -> function(n) copying data n times."""
    size = len(data)
    dst = bytearray(size)
    mv = memoryview(dst)

    def by_bytearray(n):
        for _ in range(n):
            bytearray(data)

    def mv_assign(n):
        for _ in range(n):
            mv[:] = data

    out = {'bytearray': by_bytearray, 'mv_assign': mv_assign}
    try:
        import numpy
    except ImportError:
        return out
    src, ndst = numpy.frombuffer(data, numpy.uint8), numpy.empty(size, numpy.uint8)

    def np_copy(n):
        for _ in range(n):
            numpy.copyto(ndst, src)

    out['numpy'] = np_copy
    return out


def rate(fn, block, blocks):
    """Best calls/s of fn over `blocks` timed blocks of about `block` seconds each.

    The best block, as timeit reports its minimum: on a shared machine noise only ever
    slows a block down.  Repetitions (fresh processes) are then summarised by the median.
    """
    n = 1
    while True:  # calibrate: grow n until one block takes >= block / 4
        t = rate_clock()
        fn(n)
        dt = rate_clock() - t
        if dt >= block / 4:
            break
        n *= 4 if dt < block / 40 else 2
    n = max(1, int(n * block / dt))
    rates = []
    for _ in range(blocks):
        gc.collect()
        t = rate_clock()
        fn(n)
        rates.append(n / (rate_clock() - t))
    return max(rates)


class _P:
    __slots__ = ('x', 'y')

    def __init__(self, *args, **kwds):
        self.x = 0
        self.y = 0.0


def python_loop(n):
    """A fixed workload without message classes (calls, attributes, a small C call): how fast
    is this interpreter build at all?"""
    def pack(v):
        return v.to_bytes(8, 'little')

    for i in range(n):
        p = _P()
        p.x = i
        p.y = pack(p.x)


def worker(impl, block, blocks):
    try:
        import std_msgs.msg
        msgs = build_messages()
    except ImportError as e:
        print('%s (%s)' % (e, sys.executable), file=sys.stderr)
        return MISSING_EXIT
    where = os.path.dirname(std_msgs.msg.__file__)
    if impl.startswith('kame') and not os.path.abspath(where).startswith(os.path.join(ROOT, 'src')):
        print('kame worker imported std_msgs from %s, not from this checkout' % where, file=sys.stderr)
        return 2
    if impl == 'genpy':
        import genpy
        if not isinstance(msgs['string'][1], genpy.Message):
            print('genpy worker did not import genpy messages (%s)' % where, file=sys.stderr)
            return 2
    res = {'impl': impl, 'python': sys.version.split()[0], 'executable': sys.executable,
           'std_msgs': where, 'messages': {}, 'copies': {},
           'python_loop': rate(python_loop, block, blocks)}
    for name, (cls, msg) in msgs.items():
        b = io.BytesIO()
        msg.serialize(b)
        data = b.getvalue()
        back = io.BytesIO()
        cls().deserialize(data).serialize(back)
        if back.getvalue() != data:
            print('%s: deserialize(serialize(msg)) does not round-trip' % name, file=sys.stderr)
            return 2
        r = {'bytes': len(data), 'sha256': hashlib.sha256(data).hexdigest()}
        for op, fn in loops(impl, cls, msg, data).items():
            if name in LARGE and op in SMALL_ONLY:
                continue  # kame frames large messages without copying them: no like-for-like figure
            r[op] = rate(fn, block, blocks)
        res['messages'][name] = r
        if name in LARGE:
            res['copies'][name] = {k: rate(fn, block, blocks) for k, fn in copies(data).items()}
    print(json.dumps(res), flush=True)
    return 0


# ====================================================================== driver
def run_worker(impl, prefix, o):
    """Run one worker in its own process group; return (result dict or None, exit status, error line)."""
    cmd = [*prefix, os.path.abspath(__file__), '--worker', impl, '--block', str(o.block),
           '--blocks', str(o.blocks), '--clock', o.clock]
    p = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True, start_new_session=True)
    try:
        out, err = p.communicate(timeout=o.timeout)
    except BaseException:
        for sig in (signal.SIGTERM, signal.SIGKILL):
            try:
                os.killpg(p.pid, sig)
            except ProcessLookupError:
                break
            try:
                p.wait(2)
                break
            except subprocess.TimeoutExpired:
                pass
        raise
    if p.returncode == 0:
        return json.loads(out.strip().splitlines()[-1]), p.returncode, ''
    lines = err.strip().splitlines()
    return None, p.returncode, lines[-1] if lines else 'no output'


def fmt(v):
    if v is None:
        return 'n/a'
    if abs(v) >= 100:
        return f'{v:,.0f}'
    return '%.3g' % v if abs(v) >= 1 else '%.2g' % v


def size_text(n):
    return '%d B' % n if n < 10_000 else '%.1f MB' % (n / 1e6)


def dig(r, *path):
    for k in path:
        r = r.get(k) if isinstance(r, dict) else None
    return r


def med(results, *path):
    vals = [v for v in (dig(r, *path) for r in results) if v is not None]
    return statistics.median(vals) if vals else None


def ratio(res, a, b, *path):
    """Median of the per-repetition ratios a/b (the workers of a repetition ran back to back)."""
    rs = [x / y for x, y in ((dig(ra, *path), dig(rb, *path)) for ra, rb in zip(res[a], res[b], strict=False))
          if x is not None and y]
    return '%.2fx' % statistics.median(rs) if rs else 'n/a'


def table(res, base='genpy'):
    """res[impl] = list of worker results (one per repetition).  Returns the table text."""
    names = list(res)
    others = [n for n in names if n != base]
    everyone = [r for n in names for r in res[n]]
    rows = [['message', 'size', 'op', *('%s msg/s' % n for n in names), *('%s/%s' % (n, base) for n in others),
             *('%s MB/s' % n for n in names), 'copy MB/s']]
    notes = []
    for name, label in MESSAGES:
        size = med(everyone, 'messages', name, 'bytes')
        big = name in LARGE and size
        copy_rate = med(everyone, 'copies', name, 'bytearray')
        for i, (op, op_label) in enumerate(OPS):
            if name in LARGE and op in SMALL_ONLY:
                continue
            rates = [med(res[n], 'messages', name, op) for n in names]
            rows.append([
                label if i == 0 else '', size_text(size) if i == 0 and size else '', op_label,
                *(fmt(v) for v in rates),
                *(ratio(res, n, base, 'messages', name, op) for n in others),
                *((fmt(v * size / 1e6) if v else 'n/a') if big else '' for v in rates),
                fmt(copy_rate * size / 1e6) if big and copy_rate and i == 0 else '',
            ])
        if len({dig(r, 'messages', name, 'sha256') for r in everyone} - {None}) > 1:
            notes.append('WARNING: %s does not serialize to the same bytes everywhere' % label)
    widths = [max(len(r[c]) for r in rows) for c in range(len(rows[0]))]
    lines = ['  '.join(c.ljust(w) if j < 3 else c.rjust(w)
                       for j, (c, w) in enumerate(zip(r, widths, strict=True))).rstrip() for r in rows]
    lines.insert(1, '-' * max(len(ln) for ln in lines))
    lines += ['', 'copy of the same bytes, MB/s (median over all workers; "copy MB/s" above is bytearray(b)):']
    for name, label in MESSAGES:
        size = med(everyone, 'messages', name, 'bytes')
        if name in LARGE and size:
            cells = ['%s %s' % (how, fmt(med(everyone, 'copies', name, key) * size / 1e6))
                     for key, how in COPIES if med(everyone, 'copies', name, key)]
            lines.append('  %-34s %s' % (label, '   '.join(cells)))
    loop = {n: med(res[n], 'python_loop') for n in names}
    if loop.get(base):
        lines.append('interpreter check, the same Python code without messages (/%s): %s' % (base, '  '.join(
            '%s %.2fx' % (n, loop[n] / loop[base]) for n in others if loop[n])))
    return '\n'.join(lines + notes)


def loadavg():
    with open('/proc/loadavg') as f:
        return ' '.join(f.read().split()[:3])


def driver(o):
    impls = dict(IMPLS)
    if o.kame_on_debian_python:
        impls['kame@deb'] = ['env', 'PYTHONPATH=' + os.path.join(ROOT, 'src'), IMPLS['genpy'][0]]
    for spec in o.impl:
        name, _, cmd = spec.partition('=')
        impls[name] = shlex.split(cmd)
    res, missing, failed = {name: [] for name in impls}, {}, False
    load0 = loadavg()
    for rep in range(o.reps):
        for name, prefix in impls.items():
            if name in missing:
                continue
            if not shutil.which(prefix[0]):
                missing[name] = '%s not found' % prefix[0]
                continue
            t = clock()
            r, code, err = run_worker(name, prefix, o)
            if code == MISSING_EXIT:
                missing[name] = err
                print('%-8s n/a: %s' % (name, err), file=sys.stderr, flush=True)
                continue
            if r is None:
                failed = True
                print('rep %d %-8s FAILED (exit %d): %s' % (rep + 1, name, code, err), file=sys.stderr, flush=True)
                continue
            res[name].append(r)
            print('rep %d %-8s %5.1fs  %s' % (rep + 1, name, clock() - t, '  '.join(
                '%s=%s' % (m, fmt(v['ser'])) for m, v in r['messages'].items())), file=sys.stderr, flush=True)
    print('message serialization, msg/s and MB/s (%s time), medians of %d repetitions (workers interleaved); '
          'loadavg %s -> %s' % (o.clock, o.reps, load0, loadavg()))
    for name, prefix in impls.items():
        r = res[name][0] if res[name] else None
        print('  %-8s %s' % (name, 'Python %s (%s), messages from %s' % (r['python'], ' '.join(prefix), r['std_msgs'])
                             if r else 'n/a: %s' % missing.get(name, 'failed')))
    print(table(res))
    if o.json:
        with open(o.json, 'w') as f:
            json.dump({'date': time.strftime('%Y-%m-%d %H:%M:%S %Z'), 'argv': sys.argv, 'impls': impls,
                       'results': res}, f, indent=1)
    return 1 if failed or missing else 0


def _on_signal(signum, frame):
    raise KeyboardInterrupt('signal %d' % signum)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--reps', type=int, default=3, help='worker runs per implementation (%(default)s)')
    ap.add_argument('--block', type=float, default=0.05, help='seconds per timed block (default %(default)s)')
    ap.add_argument('--blocks', type=int, default=5, help='timed blocks per measurement in a worker (best)')
    ap.add_argument('--timeout', type=float, default=600, help='seconds a worker may take')
    ap.add_argument('--kame-on-debian-python', action=argparse.BooleanOptionalAction, default=True,
                    help="also a column kame@deb: kame's classes (PYTHONPATH=src) under genpy's interpreter, "
                         "which separates codegen from interpreter build (default: on)")
    ap.add_argument('--impl', action='append', default=[], metavar='NAME=COMMAND',
                    help='add or override an implementation: NAME=interpreter command prefix')
    ap.add_argument('--clock', choices=sorted(CLOCKS), default='wall',
                    help="time blocks by wall clock or by the worker's CPU time, which a machine busy "
                         "with other work disturbs less (default %(default)s)")
    ap.add_argument('--json', help='write all per-repetition results to this file')
    ap.add_argument('--worker', help=argparse.SUPPRESS)
    o = ap.parse_args()
    if o.worker:
        global rate_clock
        rate_clock = CLOCKS[o.clock]
        return worker(o.worker, o.block, o.blocks)
    for sig in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, _on_signal)
    try:
        return driver(o)
    except KeyboardInterrupt:
        print('interrupted', file=sys.stderr)
        return 1


if __name__ == '__main__':
    sys.exit(main())
