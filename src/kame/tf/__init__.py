"""tf and tf2 as pure logic: tf.transformations and the tf2 buffer core (a frame tree of
time-stamped transforms, lookups, interpolation, errors with tf2's messages). Nothing here
reads a clock or starts a thread: the node-layer glue (kame.tfnode) feeds it messages and
waits on it."""
