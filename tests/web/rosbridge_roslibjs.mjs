// roslibjs in Node against kame's rosbridge: `node rosbridge_roslibjs.mjs ws://127.0.0.1:PORT`.
// Prints one JSON object of what it saw; test_rosbridge_roslibjs_node.py judges it.
import * as ROSLIB from "roslib";

const url = process.argv[2];
const result = {};

function connect() {
  return new Promise((resolve, reject) => {
    const ros = new ROSLIB.Ros({ url });
    ros.on("connection", () => resolve(ros));
    ros.on("error", (error) => reject(new Error(`cannot connect to ${url}: ${error}`)));
  });
}

function withTimeout(promise, what, ms = 20000) {
  return Promise.race([promise, new Promise((_, reject) => setTimeout(() => reject(new Error(`timed out: ${what}`)), ms))]);
}

function first(ros, options) {
  return withTimeout(new Promise((resolve) => {
    const topic = new ROSLIB.Topic({ ros, ...options });
    topic.subscribe((msg) => { topic.unsubscribe(); resolve(msg); });
  }), `a message with ${JSON.stringify(options)}`);
}

function call(fn, ...args) {
  return withTimeout(new Promise((resolve, reject) => fn(...args, resolve, reject)), fn.name || "a call");
}

const plain = await connect();
const pose = { name: "/turtle1/pose", messageType: "turtlesim/Pose" };
result.json = await first(plain, pose);
result.cbor = await first(await connect(), { ...pose, compression: "cbor" });
result.png = await first(await connect(), { ...pose, compression: "png" });
const raw = await first(await connect(), { ...pose, compression: "cbor-raw" });
result.cborRaw = { secs: raw.secs, nsecs: raw.nsecs, bytes: Array.from(raw.bytes) };

// CBOR's typed arrays (float64[] as tag 86) and uint8[] (bytes), decoded by roslibjs's cbor2
const joints = new ROSLIB.Topic({ ros: plain, name: "/web_joints", messageType: "sensor_msgs/JointState" });
joints.advertise();
const arrays = withTimeout(new Promise((resolve) => {
  connect().then((ros) => {
    const topic = new ROSLIB.Topic({ ros, name: "/web_joints", messageType: "sensor_msgs/JointState", compression: "cbor" });
    topic.subscribe((msg) => resolve({ name: msg.name, position: Array.from(msg.position), kind: msg.position.constructor.name }));
  });
}), "a CBOR JointState");
const sending = setInterval(() => joints.publish({ name: ["a", "b"], position: [1.5, -2.25] }), 100);
result.cborArrays = await arrays;
clearInterval(sending);

// throttle_rate 500 ms with a queue of 1: at most a few of turtlesim's ~60 poses a second
const throttled = await connect();
let count = 0;
const slow = new ROSLIB.Topic({ ros: throttled, ...pose, throttle_rate: 500, queue_length: 1 });
slow.subscribe(() => { count += 1; });
await new Promise((resolve) => setTimeout(resolve, 2000));
slow.unsubscribe();
result.throttledCount = count;

// fragments: a raw subscribe op with fragment_size, put back together by roslibjs itself
const fragmented = await connect();
result.fragmented = await withTimeout(new Promise((resolve) => {
  fragmented.on("/rosout", (op) => { if (op.msg.name === "/roslibjs") resolve(op.msg); });
  fragmented.callOnConnection({ op: "subscribe", topic: "/rosout", type: "rosgraph_msgs/Log", fragment_size: 16 });
  const rosout = new ROSLIB.Topic({ ros: plain, name: "/rosout", messageType: "rosgraph_msgs/Log" });
  const shout = () => rosout.publish({ level: 2, name: "/roslibjs", msg: "a message long enough to be cut into pieces" });
  shout();
  setInterval(shout, 200).unref();
}), "a fragmented /rosout message");

result.topics = (await call(plain.getTopics.bind(plain))).topics;
const spawn = new ROSLIB.Service({ ros: plain, name: "/spawn", serviceType: "turtlesim/Spawn" });
result.spawn = await call(spawn.callService.bind(spawn), { x: 1.0, y: 1.0, theta: 0.0, name: "node_turtle" });
const param = new ROSLIB.Param({ ros: plain, name: "/node/param" });
await call(param.set.bind(param), [1, 2, 3]);
result.param = await call(param.get.bind(param));
const missing = new ROSLIB.Service({ ros: plain, name: "/no_such_service", serviceType: "std_srvs/Empty" });
result.missingService = await call(missing.callService.bind(missing), {}).then(() => "answered", (error) => String(error));

console.log(JSON.stringify(result));
process.exit(0);
