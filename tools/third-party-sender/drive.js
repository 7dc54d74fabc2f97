#!/usr/bin/env node
// Drives CNCjs (a real, widely used third-party grbl sender) headless: starts the
// CNCjs server on a free localhost port with a private config, connects to it over
// socket.io like its web UI does, opens a serial device as a Grbl controller at
// 115200 baud, loads a G-code file, starts it and watches until CNCjs reports the
// job complete. Exit 0 only when every line was acknowledged with no error/alarm.
//
// Usage: node drive.js <device> <gcode-file> [--timeout S] [--verbose]
// Exit codes: 0 done, 1 error/alarm reported, 2 usage, 3 timeout, 4 CNCjs failed.
'use strict';

const { spawn } = require('child_process');
const crypto = require('crypto');
const fs = require('fs');
const os = require('os');
const path = require('path');

const HERE = __dirname;
const CNCJS_BIN = path.join(HERE, 'node_modules', 'cncjs', 'bin', 'cncjs');

/** Parses argv into { device, file, timeoutS, verbose } or exits 2. */
function parseArgs(argv) {
  const opts = { timeoutS: Number(process.env.SENDER_TIMEOUT || 300), verbose: !!process.env.SENDER_VERBOSE };
  const rest = [];
  for (let i = 0; i < argv.length; i++) {
    if (argv[i] === '--timeout') opts.timeoutS = Number(argv[++i]);
    else if (argv[i] === '--verbose' || argv[i] === '-v') opts.verbose = true;
    else rest.push(argv[i]);
  }
  if (rest.length !== 2 || !(opts.timeoutS > 0)) {
    console.error('usage: drive.js <device> <gcode-file> [--timeout SECONDS] [--verbose]');
    process.exit(2);
  }
  [opts.device, opts.file] = rest;
  return opts;
}

/** Loads a module from this folder's node_modules or exits 4 with a hint. */
function need(name) {
  try {
    return require(path.join(HERE, 'node_modules', name));
  } catch (err) {
    console.error(`third-party-sender: ${name} is not installed here (${err.message}); run tools/third-party-sender/setup.sh`);
    process.exit(4);
  }
}

/** Starts the CNCjs server; resolves { child, port } once it listens. */
function startCncjs(configFile, log) {
  return new Promise((resolve, reject) => {
    const env = { ...process.env, NO_COLOR: '1', FORCE_COLOR: '0' };
    const child = spawn(process.execPath, [CNCJS_BIN, '--host', '127.0.0.1', '--port', '0', '--config', configFile, '-v'],
      { env, stdio: ['ignore', 'pipe', 'pipe'] });
    let seen = '';
    const timer = setTimeout(() => reject(new Error('CNCjs did not start within 60 s')), 60000);
    const onData = (chunk) => {
      const text = chunk.toString();
      log(text);
      seen += text.replace(/\x1b\[[0-9;]*m/g, '');
      const m = seen.match(/Starting the server at http:\/\/127\.0\.0\.1:(\d+)/);
      if (m) {
        clearTimeout(timer);
        resolve({ child, port: Number(m[1]) });
      }
    };
    child.stdout.on('data', onData);
    child.stderr.on('data', onData);
    child.on('exit', (code) => { clearTimeout(timer); reject(new Error(`CNCjs exited early (code ${code})`)); });
  });
}

/** Streams the file through CNCjs; resolves { code, message }. */
function stream(opts, port, secret) {
  const io = need('socket.io-client');
  const jwt = need('jsonwebtoken');
  // CNCjs accepts any token signed with the secret of its config while the config
  // lists no users (access-control.js validateUser); this is how cncjs-pendant does it.
  const token = jwt.sign({ id: '', name: 'lathe-third-party-sender' }, secret, { expiresIn: '1h' });
  const gcode = fs.readFileSync(opts.file, 'utf8');
  const name = path.basename(opts.file);
  const say = (s) => console.log(`[cncjs] ${s}`);
  return new Promise((resolve) => {
    const socket = io.connect(`http://127.0.0.1:${port}`, { query: `token=${token}`, transports: ['websocket'], reconnection: false });
    const st = { open: false, settings: false, idle: false, started: false, running: false, total: 0, received: 0, sent: 0, lastLine: '', ended: false };
    let finished = false;
    const finish = (code, message) => {
      if (finished) return;
      finished = true;
      clearTimeout(timer);
      socket.emit('close', opts.device, () => { socket.close(); resolve({ code, message }); });
      setTimeout(() => { socket.close(); resolve({ code, message }); }, 2000);
    };
    const timer = setTimeout(() => finish(3, `timeout after ${opts.timeoutS} s: ${describe(st)}`), opts.timeoutS * 1000);

    const maybeStart = () => {
      if (st.started || !st.open || !st.idle || !st.settings) return;
      st.started = true;
      // Give the `ok` that ends the `$$` answer time to arrive before streaming:
      // CNCjs would count a late one as the answer to a program line.
      setTimeout(() => {
        socket.emit('command', opts.device, 'gcode:load', name, gcode, {}, (err, info) => {
          if (err) return finish(1, `gcode:load refused: ${err.message || err}`);
          say(`loaded ${name}: ${info.total} lines to send (CNCjs appends "%wait" = G4 P0.5)`);
          socket.emit('command', opts.device, 'gcode:start');
        });
      }, 500);
    };

    socket.on('connect_error', (err) => finish(4, `socket.io connect failed: ${err.message || err}`));
    socket.on('error', (err) => finish(4, `socket.io error: ${err.message || err}`));
    socket.on('startup', () => {
      socket.emit('open', opts.device, { controllerType: 'Grbl', baudrate: 115200, rtscts: false }, (err) => {
        if (err) return finish(4, `CNCjs could not open ${opts.device}: ${err.message || err}`);
      });
    });
    socket.on('serialport:open', (o) => { st.open = true; say(`port open: ${o.port} ${o.baudrate} ${o.controllerType}`); maybeStart(); });
    socket.on('serialport:error', (o) => finish(4, `serial port error on ${o.port}: ${o.err && (o.err.message || o.err)}`));
    socket.on('serialport:close', () => { if (!finished) finish(1, `serial port closed during the job: ${describe(st)}`); });
    socket.on('controller:settings', (type, s) => {
      if (s && s.settings && Object.keys(s.settings).length > 0) { st.settings = true; maybeStart(); }
    });
    socket.on('controller:state', (type, s) => {
      const active = s && s.status && s.status.activeState;
      if (active === 'Idle' && !st.idle) {
        st.idle = true;
        // A board whose `$$` lists no setting never triggers controller:settings.
        setTimeout(() => { st.settings = true; maybeStart(); }, 3000);
        maybeStart();
      }
      if (active === 'Alarm') finish(1, `board in Alarm: ${describe(st)}`);
    });
    socket.on('serialport:read', (line) => {
      if (opts.verbose) say(`< ${line}`);
      if (/^> /.test(line)) st.lastLine = line;
      if (/^\[MSG:/.test(line)) st.lastMsg = line;
      if (/^\[MSG:Load T\d+\]/.test(line)) onToolChange(socket, opts, () => finished, say, line);
      if (/^ALARM/.test(line)) finish(1, `${line} ${st.lastMsg || ''} ${describe(st)}`);
      if (/^error/.test(line) && st.running) finish(1, `${line} for ${errorLine(st.lastLine, gcode)}: ${describe(st)}`);
    });
    socket.on('sender:status', (s) => {
      if (s.total > 0 && s.sent > 0) Object.assign(st, { total: s.total, sent: s.sent, received: s.received });
      if (s.total > 0 && s.received >= s.total && s.finishTime > 0) st.ended = true;
      if (opts.verbose) say(`sender ${s.sent}/${s.received}/${s.total} hold=${s.hold}`);
    });
    socket.on('workflow:state', (w) => {
      if (opts.verbose) say(`workflow ${w}`);
      if (w === 'running') st.running = true;
      if (w === 'paused') onPause(socket, opts, () => finished, say);
      if (w === 'idle' && st.running) {
        st.running = false;
        if (st.ended && st.received === st.total) finish(0, `job complete: ${st.received}/${st.total} lines acknowledged`);
        else finish(1, `CNCjs stopped the job early: ${describe(st)}`);
      }
    });
  });
}

/**
 * A paused workflow. CNCjs pauses after sending a line holding M0, M1 or M6 (an
 * operator would press resume, which also sends `~`) and on an error; an error has
 * already failed the run, anything else is resumed as the operator would.
 */
function onPause(socket, opts, isFinished, say) {
  setTimeout(() => {
    if (isFinished()) return;
    say('CNCjs paused the job (M0/M1/M6 program stop); resuming as an operator would (sends ~)');
    socket.emit('command', opts.device, 'gcode:resume');
  }, 300);
}

/**
 * A tool change by hand on the board (a mill's M06): the board has stopped the
 * motion and the spindle and waits for cycle start; the operator loads the tool
 * and presses it (CNCjs's cycle start sends `~`).
 */
function onToolChange(socket, opts, isFinished, say, msg) {
  setTimeout(() => {
    if (isFinished()) return;
    say(`the board asks for a tool by hand (${msg.trim()}); cycle start as an operator would (sends ~)`);
    socket.emit('command', opts.device, 'cyclestart');
  }, 300);
}

/** One-line progress for messages. */
function describe(st) {
  if (!st.open) return 'CNCjs never opened the port';
  if (!st.idle) return 'the board never reported Idle (CNCjs needs the grbl welcome or an answer to ?)';
  return st.total > 0 ? `sent ${st.sent}, acknowledged ${st.received} of ${st.total} lines` : 'before the first progress report';
}

/**
 * The program line an error answered. CNCjs reports `> TEXT (ln=N)` where N is the
 * right line number (of the non-empty lines) but TEXT is the line before it.
 */
function errorLine(report, gcode) {
  const m = /\(ln=(\d+)\)$/.exec(report || '');
  if (!m) return report || 'an unknown line';
  const lines = gcode.split('\n').filter((l) => l.trim().length > 0);
  return `line ${m[1]} of the non-empty lines: "${(lines[Number(m[1]) - 1] || '').trim()}"`;
}

async function main() {
  const opts = parseArgs(process.argv.slice(2));
  if (!fs.existsSync(opts.device)) { console.error(`no such device: ${opts.device}`); process.exit(2); }
  if (!fs.existsSync(opts.file)) { console.error(`no such G-code file: ${opts.file}`); process.exit(2); }
  if (!fs.existsSync(CNCJS_BIN)) { console.error('CNCjs is not installed here; run tools/third-party-sender/setup.sh'); process.exit(4); }
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'cncjs-'));
  const secret = crypto.randomBytes(24).toString('hex');
  const configFile = path.join(dir, 'cncrc.json');
  // Tool change policy "Send M6 commands" (1): CNCjs's default comments M6 out and
  // pauses its own job, so the board would never see the tool change. With it sent,
  // the board stops for a change by hand (docs/MILL-BOARD.md) and says
  // [MSG:Load Tnn]; onToolChange presses cycle start as the operator would.
  const config = { secret, state: { controller: { exception: { ignoreErrors: false } } }, tool: { toolChangePolicy: 1 } };
  fs.writeFileSync(configFile, JSON.stringify(config));
  const logFile = path.join(dir, 'cncjs.log');
  const logStream = fs.createWriteStream(logFile);
  const log = (t) => { logStream.write(t); if (opts.verbose) process.stderr.write(t); };
  let child = null;
  let result;
  try {
    const started = await startCncjs(configFile, log);
    child = started.child;
    // Never leave the CNCjs server behind when we are interrupted.
    for (const sig of ['SIGINT', 'SIGTERM', 'SIGHUP']) {
      process.on(sig, () => { child.kill('SIGTERM'); console.log(`[cncjs] FAIL: interrupted (${sig})`); process.exit(1); });
    }
    console.log(`[cncjs] server on 127.0.0.1:${started.port} (log ${logFile})`);
    result = await stream(opts, started.port, secret);
  } catch (err) {
    result = { code: 4, message: err.message };
  }
  if (child) { child.removeAllListeners('exit'); child.kill('SIGTERM'); }
  logStream.end();
  if (result.code === 0 || process.env.SENDER_KEEP_LOG === '0') fs.rmSync(dir, { recursive: true, force: true });
  else console.log(`[cncjs] CNCjs server log kept in ${logFile}`);
  console.log(`[cncjs] ${result.code === 0 ? 'OK' : 'FAIL'}: ${result.message}`);
  process.exit(result.code);
}

main();
