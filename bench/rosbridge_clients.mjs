// roslibjs clients of kame's rosbridge for bench/rosbridge_bench.py (run with node; ROSLIB is the
// file path of roslib's dist/RosLib.js in tests/web/node_modules).
//   node rosbridge_clients.mjs URL TOPIC CLIENTS SECONDS
// Each client subscribes to TOPIC (std_msgs/String whose data is "N WALLTIME" from the
// publisher); prints one JSON line: per client the messages received, the highest N seen, and
// the latencies (now - WALLTIME, ms) of what it received.
const ROSLIB = await import(process.env.ROSLIB);
const [url, topic, clients, seconds] = [process.argv[2], process.argv[3], Number(process.argv[4]), Number(process.argv[5])];

function connect() {
  return new Promise((resolve, reject) => {
    const ros = new ROSLIB.Ros({ url });
    ros.on("connection", () => resolve(ros));
    ros.on("error", (error) => reject(new Error(String(error))));
  });
}

const seen = [];
for (let i = 0; i < clients; i += 1) {
  const ros = await connect();
  const record = { received: 0, highest: -1, latencies: [] };
  seen.push(record);
  new ROSLIB.Topic({ ros, name: topic, messageType: "std_msgs/String", queue_length: 0 }).subscribe((msg) => {
    const now = performance.timeOrigin + performance.now();
    const [n, stamp] = msg.data.split(" ");
    record.received += 1;
    record.highest = Math.max(record.highest, Number(n));
    record.latencies.push(now - Number(stamp) * 1000);
  });
}
console.error("subscribed");
await new Promise((resolve) => setTimeout(resolve, seconds * 1000));
// exit once the pipe took it all: process.exit() alone cuts a long write to a pipe short
process.stdout.write(JSON.stringify(seen) + "\n", () => process.exit(0));
