// ubersim viewer page: draws what ubersim_viewer pushes over its WebSocket
// (one JSON snapshot per display frame) and sends control requests back.
// Field frame: x along the long axis (to the right), y across (up), metres.
'use strict';

const TEAM_COLOURS = { yellow: '#f2d21b', blue: '#3b7cf5', unknown: '#bbbbbb' };
const ROBOT_RADIUS = 0.09;          // SSL robots are at most 0.18 m across (m)
const VELOCITY_ARROW_SECONDS = 0.5; // an arrow is how far it goes in this time (s)
const DEFAULT_GEOMETRY = {          // until the field is known: division B
  name: '(waiting for geometry)', field_length: 9, field_width: 6, boundary_width: 0.3,
  boundary_width_goal_line: 0.3, goal_substitution_area_width: 0.3, penalty_mark_distance: 6,
  line_width: 0.01, goal_width: 1, goal_depth: 0.18, goal_wall_thickness: 0.02,
  wall_thickness: 0.02, center_circle_radius: 0.5, penalty_area_depth: 1,
  penalty_area_width: 2, ball_radius: 0.0215,
};

// What the page shows, for people and for tests (window.viewerState).
const viewerState = {
  connected: false,
  framesReceived: 0,
  framesDrawn: 0,
  frame: null,         // the newest snapshot from the server
  robotsDrawn: [],     // ground-truth robots drawn: {team, id, x, y, orientation}
  visionRobotsDrawn: 0,
  ballDrawn: null,     // {x, y} of the ground-truth ball drawn
  requestsSent: [],    // control requests sent, newest last (at most 20 kept)
  game: null,          // the referee's state shown: {yellow, blue, stage, command, ...} or null
};
window.viewerState = viewerState;

const canvas = document.getElementById('field');
const context = canvas.getContext('2d');
const byId = (id) => document.getElementById(id);
let socket = null;
let view = { scale: 100, cx: 0, cy: 0 };  // field metres -> canvas CSS pixels
let drag = null;                          // {kind: 'ball'|'robot', robot, x, y}
let redrawPending = false;

// ---- connection ----------------------------------------------------------
function connect() {
  socket = new WebSocket(`ws://${location.host}/`);
  socket.onopen = () => { viewerState.connected = true; showConnection(); };
  socket.onclose = () => {
    viewerState.connected = false;
    showConnection();
    setTimeout(connect, 1000);
  };
  socket.onmessage = (event) => {
    const message = JSON.parse(event.data);
    if (message.type !== 'frame') return;
    viewerState.frame = message;
    viewerState.framesReceived += 1;
    scheduleRedraw();
  };
}

function showConnection() {
  const element = byId('connection');
  element.textContent = viewerState.connected ? 'connected' : 'disconnected: retrying…';
  element.className = viewerState.connected ? 'good' : 'bad';
}

function send(request) {
  if (!socket || socket.readyState !== WebSocket.OPEN) return false;
  socket.send(JSON.stringify(request));
  viewerState.requestsSent.push(request);
  if (viewerState.requestsSent.length > 20) viewerState.requestsSent.shift();
  return true;
}

// ---- geometry and coordinates -------------------------------------------
function geometry() {
  return (viewerState.frame && viewerState.frame.geometry) || DEFAULT_GEOMETRY;
}

function updateView() {
  const ratio = window.devicePixelRatio || 1;
  const width = canvas.clientWidth, height = canvas.clientHeight;
  if (canvas.width !== Math.round(width * ratio) || canvas.height !== Math.round(height * ratio)) {
    canvas.width = Math.round(width * ratio);
    canvas.height = Math.round(height * ratio);
  }
  const g = geometry();
  const halfX = g.field_length / 2 + goalLineBoundary(g) + g.wall_thickness + 0.05;
  const halfY = g.field_width / 2 + g.boundary_width + g.wall_thickness + 0.05;
  const scale = Math.min(width / (2 * halfX), height / (2 * halfY));
  view = { scale, cx: width / 2, cy: height / 2, ratio };
}

function toCanvas(x, y) { return [view.cx + x * view.scale, view.cy - y * view.scale]; }
function toField(px, py) { return [(px - view.cx) / view.scale, (view.cy - py) / view.scale]; }

// ---- drawing -------------------------------------------------------------
function scheduleRedraw() {
  if (redrawPending) return;
  redrawPending = true;
  requestAnimationFrame(() => { redrawPending = false; draw(); });
}

function draw() {
  updateView();
  context.setTransform(view.ratio, 0, 0, view.ratio, 0, 0);
  context.fillStyle = '#1f5f2a';
  context.fillRect(0, 0, canvas.clientWidth, canvas.clientHeight);
  drawField(geometry());
  const frame = viewerState.frame;
  const state = frame && frame.state;
  viewerState.robotsDrawn = [];
  viewerState.visionRobotsDrawn = 0;
  viewerState.ballDrawn = null;
  if (frame) {
    if (byId('show-vision').checked) drawVision(frame);
    if (state && byId('show-truth').checked) drawTruth(state);
    if (state && byId('show-commands').checked) drawCommands(frame.commands, state);
  }
  if (drag) drawDragGhost();
  if (frame && frame.referee) drawScoreboard(frame.referee);
  viewerState.framesDrawn += 1;
  updatePanel(frame);
}

function line(x1, y1, x2, y2) {
  const [a, b] = toCanvas(x1, y1), [c, d] = toCanvas(x2, y2);
  context.beginPath(); context.moveTo(a, b); context.lineTo(c, d); context.stroke();
}

function rect(x1, y1, x2, y2, fill) {
  const [a, b] = toCanvas(Math.min(x1, x2), Math.max(y1, y2));
  const w = Math.abs(x2 - x1) * view.scale, h = Math.abs(y2 - y1) * view.scale;
  if (fill) { context.fillRect(a, b, w, h); } else { context.strokeRect(a, b, w, h); }
}

// The margin behind the goal lines (SSL geometry field 16); older bridges
// sent only the one along the touch lines.
function goalLineBoundary(g) {
  return g.boundary_width_goal_line === undefined ? g.boundary_width : g.boundary_width_goal_line;
}

function drawField(g) {
  const L = g.field_length / 2, W = g.field_width / 2;
  const outerX = L + goalLineBoundary(g), outerY = W + g.boundary_width;
  // Goal substitution areas: the strip in front of the wall behind each goal line.
  const sub = g.goal_substitution_area_width || 0;
  if (sub > 0) {
    context.fillStyle = 'rgba(255,255,255,0.08)';
    rect(-outerX, -outerY, -outerX + sub, outerY, true);
    rect(outerX - sub, -outerY, outerX, outerY, true);
  }
  // Walls: a dark band just outside the boundary area.
  context.fillStyle = '#333';
  const t = Math.max(g.wall_thickness, 0.02);
  rect(-outerX - t, outerY, outerX + t, outerY + t, true);
  rect(-outerX - t, -outerY - t, outerX + t, -outerY, true);
  rect(-outerX - t, -outerY, -outerX, outerY, true);
  rect(outerX, -outerY, outerX + t, outerY, true);
  // Lines.
  context.strokeStyle = '#ffffff';
  context.lineWidth = Math.max(1, g.line_width * view.scale);
  rect(-L, -W, L, W, false);
  line(0, -W, 0, W);
  const [cx, cy] = toCanvas(0, 0);
  context.beginPath();
  context.arc(cx, cy, g.center_circle_radius * view.scale, 0, 2 * Math.PI);
  context.stroke();
  const pd = g.penalty_area_depth, pw = g.penalty_area_width / 2;
  rect(-L, -pw, -L + pd, pw, false);
  rect(L - pd, -pw, L, pw, false);
  // Penalty marks: penalty_mark_distance from the centre of the goal attacked.
  if (g.penalty_mark_distance !== undefined) {
    context.fillStyle = '#ffffff';
    for (const side of [-1, 1]) {
      const [px, py] = toCanvas(side * (L - g.penalty_mark_distance), 0);
      context.beginPath();
      context.arc(px, py, Math.max(2, 0.02 * view.scale), 0, 2 * Math.PI);
      context.fill();
    }
  }
  // Goals: the walls around each goal's inside, behind the goal lines.
  const gw = g.goal_width / 2, gd = g.goal_depth, gt = Math.max(g.goal_wall_thickness, 0.01);
  for (const side of [-1, 1]) {
    context.fillStyle = side < 0 ? 'rgba(242,210,27,0.25)' : 'rgba(59,124,245,0.25)';
    rect(side * L, -gw, side * (L + gd), gw, true);
    context.fillStyle = '#dddddd';
    rect(side * L, gw, side * (L + gd + gt), gw + gt, true);
    rect(side * L, -gw - gt, side * (L + gd + gt), -gw, true);
    rect(side * (L + gd), -gw, side * (L + gd + gt), gw, true);
  }
}

function arrow(x, y, dx, dy, colour) {
  const length = Math.hypot(dx, dy);
  if (!(length > 1e-3)) return;
  const [a, b] = toCanvas(x, y), [c, d] = toCanvas(x + dx, y + dy);
  context.strokeStyle = colour;
  context.fillStyle = colour;
  context.lineWidth = 2;
  context.beginPath(); context.moveTo(a, b); context.lineTo(c, d); context.stroke();
  const angle = Math.atan2(d - b, c - a), head = 7;
  context.beginPath();
  context.moveTo(c, d);
  context.lineTo(c - head * Math.cos(angle - 0.4), d - head * Math.sin(angle - 0.4));
  context.lineTo(c - head * Math.cos(angle + 0.4), d - head * Math.sin(angle + 0.4));
  context.closePath();
  context.fill();
}

function drawRobot(team, id, x, y, orientation, solid, label) {
  const [px, py] = toCanvas(x, y);
  const r = Math.max(3, ROBOT_RADIUS * view.scale);
  context.beginPath();
  context.arc(px, py, r, 0, 2 * Math.PI);
  if (solid) {
    context.fillStyle = TEAM_COLOURS[team] || TEAM_COLOURS.unknown;
    context.fill();
    context.strokeStyle = '#111';
    context.lineWidth = 1;
    context.stroke();
  } else {
    context.setLineDash([4, 3]);
    context.strokeStyle = TEAM_COLOURS[team] || TEAM_COLOURS.unknown;
    context.lineWidth = 2;
    context.stroke();
    context.setLineDash([]);
  }
  if (orientation !== null && orientation !== undefined) {
    context.strokeStyle = solid ? '#111' : TEAM_COLOURS[team];
    context.lineWidth = 2;
    context.beginPath();
    context.moveTo(px, py);
    context.lineTo(px + r * Math.cos(orientation), py - r * Math.sin(orientation));
    context.stroke();
  }
  context.fillStyle = solid ? (team === 'yellow' ? '#000' : '#fff') : TEAM_COLOURS[team];
  context.font = `bold ${Math.max(9, Math.round(r * 0.9))}px sans-serif`;
  context.textAlign = 'center';
  context.textBaseline = 'middle';
  if (solid) {
    context.fillText(String(id), px - r * 0.3 * Math.cos(orientation || 0),
                     py + r * 0.3 * Math.sin(orientation || 0));
  } else {
    context.fillText(label, px + r + 6, py - r);
  }
}

function drawBall(x, y, solid) {
  const g = geometry();
  const [px, py] = toCanvas(x, y);
  context.beginPath();
  context.arc(px, py, Math.max(3, g.ball_radius * view.scale), 0, 2 * Math.PI);
  if (solid) {
    context.fillStyle = '#ff8c1a';
    context.fill();
  } else {
    context.strokeStyle = '#ffb366';
    context.lineWidth = 2;
    context.stroke();
  }
}

function drawTruth(state) {
  for (const robot of state.robots) {
    if (robot.x === null || robot.y === null) continue;
    drawRobot(robot.team, robot.id, robot.x, robot.y, robot.orientation, true);
    viewerState.robotsDrawn.push({ team: robot.team, id: robot.id, x: robot.x, y: robot.y,
                                   orientation: robot.orientation });
  }
  const ball = state.ball;
  if (ball && ball.x !== null && ball.y !== null) {
    drawBall(ball.x, ball.y, true);
    viewerState.ballDrawn = { x: ball.x, y: ball.y };
    if (byId('show-ball-velocity').checked) {
      arrow(ball.x, ball.y, ball.vx * VELOCITY_ARROW_SECONDS, ball.vy * VELOCITY_ARROW_SECONDS,
            '#ff8c1a');
    }
  }
}

function cameraEnabled(cameraId) {
  const toggle = byId(`camera-${cameraId}`);
  return !toggle || toggle.checked;
}

function drawVision(frame) {
  for (const camera of frame.vision) {
    if (!cameraEnabled(camera.camera_id)) continue;
    for (const team of ['yellow', 'blue']) {
      for (const robot of camera[team]) {
        drawRobot(team, robot.id, robot.x, robot.y, robot.orientation, false,
                  `c${camera.camera_id}`);
        viewerState.visionRobotsDrawn += 1;
      }
    }
    for (const ball of camera.balls) drawBall(ball.x, ball.y, false);
  }
}

function drawCommands(commands, state) {
  for (const team of ['yellow', 'blue']) {
    const packet = commands && commands[team];
    if (!packet) continue;
    for (const command of packet.commands) {
      const robot = state.robots.find((r) => r.team === team && r.id === command.id);
      if (!robot || command.mode === 'wheels') continue;
      let vx = command.vx, vy = command.vy;
      if (command.mode === 'local') {  // robot frame -> field frame
        const c = Math.cos(robot.orientation), s = Math.sin(robot.orientation);
        [vx, vy] = [c * command.vx - s * command.vy, s * command.vx + c * command.vy];
      }
      arrow(robot.x, robot.y, vx * VELOCITY_ARROW_SECONDS, vy * VELOCITY_ARROW_SECONDS, '#ff4fd8');
    }
  }
}

function drawDragGhost() {
  context.globalAlpha = 0.5;
  if (drag.kind === 'ball') {
    drawBall(drag.x, drag.y, true);
  } else {
    drawRobot(drag.robot.team, drag.robot.id, drag.x, drag.y, drag.robot.orientation, true);
  }
  context.globalAlpha = 1;
}

// ---- the game (REFEREE) ---------------------------------------------------
// A team's name when the referee gives one, else its colour.
function teamName(referee, team) {
  const name = referee[team] && referee[team].name;
  return typeof name === 'string' && name.length > 0 ? name : team;
}

// 283.4 s -> "4:44" (a clock counting down shows the second it is in); below zero with a minus.
function clockText(seconds) {
  if (seconds === null || seconds === undefined) return '–';
  const whole = Math.ceil(Math.abs(seconds));
  const text = `${Math.floor(whole / 60)}:${String(whole % 60).padStart(2, '0')}`;
  return seconds < 0 ? `-${text}` : text;
}

// The score, stage and command across the top of the field.
function drawScoreboard(referee) {
  const text = `${teamName(referee, 'yellow')} ${referee.yellow.score} : ` +
               `${referee.blue.score} ${teamName(referee, 'blue')}   ${referee.stage} ` +
               `${clockText(referee.stage_time_left)}   ${referee.command}`;
  context.font = 'bold 14px sans-serif';
  context.textAlign = 'center';
  context.textBaseline = 'top';
  const width = context.measureText(text).width + 16;
  context.fillStyle = 'rgba(0,0,0,0.55)';
  context.fillRect(canvas.clientWidth / 2 - width / 2, 4, width, 22);
  context.fillStyle = '#ffffff';
  context.fillText(text, canvas.clientWidth / 2, 8);
}

function updateGame(referee) {
  if (!referee) return;
  byId('yellow-name').textContent = teamName(referee, 'yellow');
  byId('blue-name').textContent = teamName(referee, 'blue');
  byId('yellow-score').textContent = String(referee.yellow.score);
  byId('blue-score').textContent = String(referee.blue.score);
  byId('game-stage').textContent = referee.game_over ? `${referee.stage} (game over)` : referee.stage;
  byId('game-time-left').textContent = clockText(referee.stage_time_left);
  byId('game-command').textContent = referee.command;
  byId('game-next-command').textContent = referee.next_command || '–';
  const last = referee.events[referee.events.length - 1];
  if (last) byId('game-event').textContent = last.description || last.type;
  viewerState.game = {
    yellow: referee.yellow.score, blue: referee.blue.score, stage: referee.stage,
    command: referee.command, next_command: referee.next_command,
    ball_in_play: referee.ball_in_play, sim_time: referee.sim_time,
  };
}

// ---- side panel ----------------------------------------------------------
function speedText(factor) {
  if (factor === null || factor === undefined) return '–';
  if (factor < 0) return 'lockstep';
  if (factor === 0) return 'as fast as possible';
  return `${factor}× real time`;
}

function updatePanel(frame) {
  const state = frame && frame.state;
  byId('sim-time').textContent = state ? `${state.sim_time.toFixed(3)} s` : '–';
  byId('sim-step').textContent = state ? String(state.step) : '–';
  byId('sim-speed').textContent = state ? speedText(state.speed_factor) : '–';
  byId('sim-paused').textContent = state ? (state.paused ? 'paused' : 'running') : '–';
  byId('pause-button').textContent = state && state.paused ? 'Resume' : 'Pause';
  byId('field-name').textContent = geometry().name;
  byId('robot-count').textContent = String(viewerState.robotsDrawn.length);
  if (!frame) return;
  updateGame(frame.referee);
  const rows = Object.entries(frame.rates)
      .map(([channel, rate]) => `<tr><th>${channel}</th><td>${rate.toFixed(1)}</td></tr>`);
  byId('rates').innerHTML = rows.join('');
  updateCameras(frame, state);
  if (frame.ack) {
    byId('ack').textContent = `${frame.ack.ok ? 'done' : 'refused'}: ${frame.ack.message}`;
  }
  const server = frame.server || {};
  byId('server').textContent =
      `pages ${server.clients}, ${server.display_rate} frames/s, ` +
      `frames skipped for slow pages ${server.frames_skipped}`;
}

function updateCameras(frame, state) {
  const toggles = byId('camera-toggles');
  const rows = ['<tr><th>cam</th><th>frame</th><th>age</th><th>Y</th><th>B</th><th>balls</th></tr>'];
  for (const camera of frame.vision) {
    if (!byId(`camera-${camera.camera_id}`)) {
      const label = document.createElement('label');
      label.innerHTML = `<input type="checkbox" id="camera-${camera.camera_id}" checked> ` +
                        `camera ${camera.camera_id}`;
      label.querySelector('input').addEventListener('change', scheduleRedraw);
      toggles.appendChild(label);
    }
    // Age: how old the detections are at the sim time shown (latency + time since the frame).
    const age = state ? `${Math.round((state.sim_time - camera.t_capture) * 1000)} ms` : '–';
    rows.push(`<tr><td>${camera.camera_id}</td><td>${camera.frame_number}</td><td>${age}</td>` +
              `<td>${camera.yellow.length}</td><td>${camera.blue.length}</td>` +
              `<td>${camera.balls.length}</td></tr>`);
  }
  byId('cameras').innerHTML = rows.join('');
}

// ---- controls ------------------------------------------------------------
byId('pause-button').addEventListener('click', () => {
  const state = viewerState.frame && viewerState.frame.state;
  send({ action: state && state.paused ? 'resume' : 'pause' });
});
byId('reset-button').addEventListener('click', () => send({ action: 'reset' }));
byId('speed-select').addEventListener('change', (event) => {
  send({ action: 'speed', factor: Number(event.target.value) });
});
for (const id of ['show-truth', 'show-vision', 'show-commands', 'show-ball-velocity']) {
  byId(id).addEventListener('change', scheduleRedraw);
}

function eventToField(event) {
  const bounds = canvas.getBoundingClientRect();
  return toField(event.clientX - bounds.left, event.clientY - bounds.top);
}

// What is under the pointer: the ball first (it is small), then the nearest robot.
function pick(x, y) {
  const state = viewerState.frame && viewerState.frame.state;
  if (!state) return null;
  const ballPickRadius = Math.max(0.1, 8 / view.scale);
  if (state.ball && Math.hypot(state.ball.x - x, state.ball.y - y) < ballPickRadius) {
    return { kind: 'ball' };
  }
  let best = null, bestDistance = ROBOT_RADIUS * 1.3;
  for (const robot of state.robots) {
    const distance = Math.hypot(robot.x - x, robot.y - y);
    if (distance < bestDistance) { best = robot; bestDistance = distance; }
  }
  return best ? { kind: 'robot', robot: best } : null;
}

canvas.addEventListener('mousedown', (event) => {
  const [x, y] = eventToField(event);
  const picked = pick(x, y);
  if (!picked) return;
  drag = { ...picked, x, y };
  event.preventDefault();
  scheduleRedraw();
});
window.addEventListener('mousemove', (event) => {
  if (!drag) return;
  [drag.x, drag.y] = eventToField(event);
  scheduleRedraw();
});
window.addEventListener('mouseup', (event) => {
  if (!drag) return;
  const [x, y] = eventToField(event);
  if (drag.kind === 'ball') {
    send({ action: 'place_ball', x, y });
  } else {
    send({ action: 'place_robot', team: drag.robot.team, id: drag.robot.id, x, y,
           orientation: drag.robot.orientation });
  }
  drag = null;
  scheduleRedraw();
});
window.addEventListener('resize', scheduleRedraw);

// For tests and scripts: where a field point is on the page (CSS pixels of the viewport).
window.viewerDebug = {
  fieldToPage(x, y) {
    updateView();
    const bounds = canvas.getBoundingClientRect();
    const [px, py] = toCanvas(x, y);
    return { x: bounds.left + px, y: bounds.top + py };
  },
};

connect();
draw();
