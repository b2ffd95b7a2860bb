"""rostopic's publishing functions in a process of their own (create_publisher makes it the
anonymous node `rostopic`): publishes "hi" latched on /facade_out, waits for a subscriber and
prints what the test checks."""

import sys
import time

import rostopic

try:
    rostopic.create_publisher("/x", "std_msgs/Nope", False)
except rostopic.ROSTopicException as exc:
    print("bad type:", str(exc).splitlines()[0], flush=True)
pub, cls = rostopic.create_publisher("facade_out", "std_msgs/String", latch=True)
print("class:", cls._type, pub.resolved_name, flush=True)
try:
    rostopic.publish_message(pub, cls, [1, 2])
except rostopic.ROSTopicException as exc:
    print("bad args:", str(exc).splitlines()[0], flush=True)
print("file:", list(rostopic.file_yaml_arg(sys.argv[1])()), flush=True)
rostopic.publish_message(pub, cls, [{"data": "hi"}], once=True)
try:
    rostopic.param_publish_once(pub, cls, "/no_such_param", False)
except rostopic.ROSTopicException as exc:
    print("no param:", exc, flush=True)
print("published", flush=True)
started = time.monotonic()
rostopic.wait_for_subscriber(pub, 60)
# the subscriber (rostopic echo -n 1) may be gone again by now: what counts is that it ended the wait
print("subscriber came:", time.monotonic() - started < 50, flush=True)
