// roslibjs's Ros.authenticate in Node against kame's rosbridge with authenticate:=true:
// `node rosbridge_roslibjs_auth.mjs ws://127.0.0.1:PORT '{"good": [...], "bad": [...]}'`, each list the
// seven arguments of authenticate(mac, client, dest, rand, t, level, end). Prints one JSON object of
// what it saw: the first pose through the good connection, and whether the bad one was closed.
import * as ROSLIB from "roslib";

const url = process.argv[2];
const credentials = JSON.parse(process.argv[3]);

function withTimeout(promise, what, ms = 20000) {
  return Promise.race([promise, new Promise((_, reject) => setTimeout(() => reject(new Error(`timed out: ${what}`)), ms))]);
}

function authenticated(args) {
  const ros = new ROSLIB.Ros({ url });
  ros.authenticate(...args);
  return ros;
}

const good = authenticated(credentials.good);
const pose = await withTimeout(new Promise((resolve) => {
  const topic = new ROSLIB.Topic({ ros: good, name: "/turtle1/pose", messageType: "turtlesim/Pose" });
  topic.subscribe((msg) => { topic.unsubscribe(); resolve(msg); });
}), "a pose after a good authenticate");

const bad = authenticated(credentials.bad);
const badClosed = await withTimeout(new Promise((resolve) => {
  bad.on("close", () => resolve(true));
  bad.on("connection", () => new ROSLIB.Topic({ ros: bad, name: "/turtle1/pose", messageType: "turtlesim/Pose" })
    .subscribe(() => resolve(false)));
}), "the bad connection closed");

good.close();
console.log(JSON.stringify({ pose, badClosed }));
process.exit(0);
