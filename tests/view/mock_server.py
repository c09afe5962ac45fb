#!/usr/bin/env python3
"""A stand-in for pbfengine's live-view server (the same protocol), to develop and test the page
without building the engine. It fakes a dam break: a block of water that slumps along a box tank.
Prints the page's URL (with its token) as its first line of stdout, then serves until killed.
Besides the protocol, POST /mock?token=T takes test commands: {"command":"newrun"} (a new run_id),
{"command":"drop"} (closes the event streams), {"command":"down","seconds":S} (drops them and
answers /events with 503 for S seconds)."""
import argparse, contextlib, json, math, queue, secrets, sys, threading, time
from array import array
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from urllib.parse import parse_qs, urlsplit

PAGE = Path(__file__).resolve().parents[2] / 'engine' / 'view' / 'page'
THREE = Path('/usr/share/javascript/three')
STATIC = {'/view.js': (PAGE / 'view.js', 'text/javascript'), '/view.css': (PAGE / 'view.css', 'text/css'),
          '/three.min.js': (THREE / 'build/three.min.js', 'text/javascript'),
          '/OrbitControls.js': (THREE / 'examples/js/controls/OrbitControls.js', 'text/javascript')}
FIELDS = {'speed': 'm/s', 'density': 'kg/m^3', 'pressure': 'Pa', 'id': '-'}
COLUMNS = [('step', '-'), ('time', 's'), ('front', 'm'), ('kinetic', 'J'), ('vmax', 'm/s'), ('iterations', '-')]
G, H, A, L, W, DX, DT = 9.81, 0.5, 0.5, 1.6, 0.3, 0.025, 0.001   # column height/length, tank, spacing, step


def sse(name, data):
    return f'event: {name}\ndata: {json.dumps(data)}\n\n'


class Sim:
    """The fake run; every field is guarded by lock, and events go to every client queue."""

    def __init__(self, last_step, rate):
        self.lock, self.clients, self.last_step, self.rate = threading.Lock(), [], last_step, rate
        self.ny, self.down_until = round(W / DX), 0.0
        self.count = round(A / DX) * self.ny * round(H / DX)
        self.reset()

    def reset(self):
        self.run_id, self.step, self.state, self.color = secrets.token_hex(8), 0, 'running', 'speed'
        self.rows, self.log, self.seq, self.frame, self.frame_event = [], [], 0, b'', None
        self.taken, self.published, self.pending_steps, self.started = True, 0.0, 0, time.time()
        self.dirty = True   # a frame of the present state is due
        self.log.append('[info] run ' + self.run_id + ': dambreak.lua, %d particles' % self.count)

    def greeting(self):
        """What a client gets first: hello, then the rows and lines kept so far, the status and last frame."""
        return [sse('hello', self.hello())] + [sse('thermo', r) for r in self.rows] + \
            [sse('log', {'lines': self.log[-500:]}), sse('status', self.status())] + \
            ([sse('frame', self.frame_event)] if self.frame_event else [])

    def broadcast(self, text):
        for q in self.clients:
            q.put(text)

    def later(self, text):
        with self.lock:
            self.broadcast(text)

    def say(self, *lines):
        self.log.extend(lines)
        self.broadcast(sse('log', {'lines': list(lines)}))

    def hello(self):
        lo, hi = [0, 0, 0], [L, W, 0.8]
        return {'run_id': self.run_id, 'title': 'dambreak.lua', 'particles': self.count,
                'fields': list(FIELDS), 'color': self.color, 'domain': {'lo': lo, 'hi': hi}, 'spacing': DX,
                'columns': [{'name': n, 'unit': u} for n, u in COLUMNS], 'state': self.state,
                'plan': {'first_step': 0, 'last_step': self.last_step or None,
                         'end_time': self.last_step * DT if self.last_step else None}}

    def status(self):
        elapsed = max(time.time() - self.started, 1e-3)
        sps = self.step / elapsed if self.state == 'running' else 0.0
        left = (self.last_step - self.step) / sps if self.last_step and sps > 0 else None
        return {'step': self.step, 'time': self.step * DT, 'steps_per_second': round(sps, 1),
                'seconds_left': left, 'state': self.state, 'particles': self.count}

    def make_frame(self):
        """The slumping column: the block's particles laid out again on the lattice, column by column
        under a Ritter-like surface that sloshes once the front reaches the far wall."""
        t, n2 = self.step * DT, self.count // self.ny
        front = min(A + 2 * math.sqrt(G * H) * t, L)
        tilt = 0.5 * math.sin(4 * t) * math.exp(-0.5 * t) if front >= L else 0.0
        ncol = max(1, int(front / DX))
        prof = [max(0.05, (1 - 0.8 * ((c + 0.5) / ncol) ** 2) * (1 + tilt * ((c + 0.5) / ncol - 0.5))) for c in range(ncol)]
        counts = [max(1, round(n2 * p / sum(prof))) for p in prof]
        cells = [(c, k) for c in range(ncol) for k in range(counts[c])][:n2]
        cells += [(ncol - 1, counts[-1] + k) for k in range(n2 - len(cells))]
        pos, val = array('f'), array('f')
        for j in range(self.ny):
            for i, (c, k) in enumerate(cells):
                x, z, hc = (c + 0.5) * DX, (k + 0.5) * DX, counts[c] * DX
                pos.extend((x, (j + 0.5) * DX, z))
                u = (2 * math.sqrt(G * H) if front < L else 3 * tilt) * x / front
                val.append({'speed': abs(u) + 0.3 * z, 'density': 1000 + 3 * math.sin(x * 40 + t * 9) + 10 * (hc - z),
                            'pressure': 1000 * G * (hc - z), 'id': j * n2 + i}[self.color])
        if sys.byteorder != 'little':
            pos.byteswap(); val.byteswap()
        head = b'PBFV' + len(val).to_bytes(4, 'little') + array('d', [t]).tobytes() + \
            self.step.to_bytes(8, 'little') + self.seq.to_bytes(4, 'little') + bytes(4)
        self.frame = head + pos.tobytes() + val.tobytes()
        self.frame_event = {'seq': self.seq, 'step': self.step, 'time': t, 'count': len(val), 'color': self.color,
                            'unit': FIELDS[self.color], 'min': min(val), 'max': max(val), 'solids_version': 1}
        self.broadcast(sse('frame', self.frame_event))
        self.seq, self.taken, self.published, self.dirty = self.seq + 1, False, time.time(), False

    def advance(self):
        self.step += 1
        t = self.step * DT
        self.dirty = self.dirty or self.step % 5 == 0
        if self.step % 10 == 0:
            front = min(A + 2 * math.sqrt(G * H) * t, L)
            row = {'step': self.step, 'values': [self.step, t, front, 0.5 * 150 * (2 * math.sqrt(G * H)) ** 2 *
                                                 min(t, 0.3) * math.exp(-t), 2 * math.sqrt(G * H) * math.exp(-0.3 * t),
                                                 3 + (self.step // 70) % 3]}
            self.rows.append(row)
            self.broadcast(sse('thermo', row))
        if self.step % 100 == 0:
            self.say('[info] step %d t=%.4f s dt=%.1e iterations %d' % (self.step, t, DT, 3 + self.step % 3))
        if self.step % 700 == 0:
            self.say('[warn] density error 1.2%% above the target at step %d' % self.step)
        if self.last_step and self.step >= self.last_step:
            self.finish('[info] reached the last step %d' % self.step)

    def finish(self, line):
        self.state = 'finished'
        self.say(line, '[info] restart written to out/restart_%06d.pbfr' % self.step)

    def run(self):
        last_status = 0.0
        while True:
            time.sleep(1.0 / self.rate)
            with self.lock:
                if self.state == 'running' or self.pending_steps:
                    self.advance()
                    self.pending_steps = max(0, self.pending_steps - 1)
                if self.dirty and (self.taken or time.time() - self.published > 2):
                    self.make_frame()   # only as fast as a page takes them
                if time.time() - last_status > 0.5:
                    self.broadcast(sse('status', self.status()))
                    last_status = time.time()

    def control(self, cmd):
        c = cmd.get('command')
        if c in ('pause', 'resume', 'step', 'stop') and self.state == 'finished':
            return 400, {'error': 'the run has finished'}
        if c in ('pause', 'resume'):
            self.state = {'pause': 'paused', 'resume': 'running'}[c]
            self.say('[info] %s at step %d' % (self.state, self.step))
        elif c == 'step':
            self.state, self.pending_steps = 'paused', self.pending_steps + 1
        elif c == 'stop':
            self.finish('[info] stop requested at step %d' % self.step)
        elif c == 'color':
            if cmd.get('field') not in FIELDS:
                return 400, {'error': 'unknown field %r' % cmd.get('field')}
            self.color, self.dirty = cmd['field'], True
        elif c == 'picture':
            cam = cmd.get('camera') or {}
            ok = all(len(cam.get(k) or []) == 3 for k in ('position', 'target', 'up')) and cam.get('fov', 0) > 0
            if not ok or not cmd.get('width') or not cmd.get('height'):
                return 400, {'error': 'picture needs camera position, target, up, fov and width, height'}
            ev = sse('picture', {'path': 'out/view_%06d.png' % self.step, 'step': self.step})
            threading.Timer(0.3, self.later, (ev,)).start()   # the engine renders at the end of a step
        else:
            return 400, {'error': 'unknown command %r' % c}
        return 200, {'ok': True}


class Handler(BaseHTTPRequestHandler):
    log_message = lambda self, *args: None   # quiet

    def reply(self, code, body, ctype='application/json'):
        data = body if isinstance(body, bytes) else (json.dumps(body) if ctype == 'application/json' else body).encode()
        self.send_response(code)
        self.send_header('Content-Type', ctype)
        self.send_header('Content-Length', str(len(data)))
        self.send_header('Cache-Control', 'no-store')
        self.end_headers()
        with contextlib.suppress(BrokenPipeError, ConnectionResetError):   # the page went away
            self.wfile.write(data)

    def allowed(self, need_token):
        """The engine's checks: Host is this server, an Origin is the same, the token matches."""
        host, origin = self.headers.get('Host', ''), self.headers.get('Origin')
        hosts = {f'{n}:{self.server.server_port}' for n in ('127.0.0.1', 'localhost', '[::1]')}
        if host not in hosts or (origin is not None and origin != 'http://' + host):
            return False
        return not need_token or parse_qs(urlsplit(self.path).query).get('token', [''])[0] == TOKEN

    def do_GET(self):
        path, sim = urlsplit(self.path).path, SIM
        if path in STATIC:
            file, ctype = STATIC[path]
            return self.reply(200, file.read_bytes(), ctype) if self.allowed(False) else self.reply(403, 'forbidden', 'text/plain')
        if path not in ('/', '/index.html', '/events', '/frame', '/solids'):
            return self.reply(404, 'not found', 'text/plain')
        if not self.allowed(True):
            return self.reply(403, 'forbidden: open the URL with its token', 'text/plain')
        if path in ('/', '/index.html'):
            return self.reply(200, (PAGE / 'index.html').read_bytes(), 'text/html; charset=utf-8')
        if path == '/solids':   # the tank, a closed box whose inside the page shows
            v = [[x, y, z] for z in (0, 0.8) for y in (0, W) for x in (0, L)]
            tris = [0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5]
            return self.reply(200, {'version': 1, 'solids': [{'name': 'tank', 'container': True,
                                                             'vertices': sum(v, []), 'triangles': tris}]})
        if path == '/frame':
            with sim.lock:
                data, sim.taken = sim.frame, True
            return self.reply(200, data, 'application/octet-stream') if data else self.reply(404, {'error': 'no frame yet'})
        if time.time() < sim.down_until:
            return self.reply(503, 'the engine is restarting', 'text/plain')
        self.send_response(200)
        self.send_header('Content-Type', 'text/event-stream')
        self.send_header('Cache-Control', 'no-store')
        self.end_headers()
        q = queue.Queue()
        with sim.lock:   # the replay and joining the broadcast at once, so that nothing is lost between
            first = sim.greeting()
            sim.clients.append(q)
        with contextlib.suppress(BrokenPipeError, ConnectionResetError):
            item = ''.join(first)
            while item is not None:   # None: the stream is dropped
                self.wfile.write(item.encode())
                self.wfile.flush()
                try:
                    item = q.get(timeout=15)
                except queue.Empty:
                    item = ': keep-alive\n\n'
        with sim.lock:
            sim.clients.remove(q)

    def do_POST(self):
        path, sim = urlsplit(self.path).path, SIM
        if path not in ('/control', '/mock'):
            return self.reply(404, {'error': 'not found'})
        if not self.allowed(True):
            return self.reply(403, {'error': 'forbidden'})
        try:
            cmd = json.loads(self.rfile.read(int(self.headers.get('Content-Length') or 0)) or b'{}')
        except ValueError:
            return self.reply(400, {'error': 'the body is not JSON'})
        with sim.lock:
            if path == '/control':
                return self.reply(*sim.control(cmd))
            if cmd.get('command') == 'newrun':
                sim.reset()
                sim.broadcast(''.join(sim.greeting()))
            elif cmd.get('command') in ('drop', 'down'):
                sim.down_until = time.time() + float(cmd.get('seconds', 0))
                sim.broadcast(None)
        return self.reply(200, {'ok': True})


if __name__ == '__main__':
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--port', type=int, default=0, help='0: a free port')
    ap.add_argument('--steps', type=int, default=3000, help='last step (0: no end)')
    ap.add_argument('--rate', type=float, default=100, help='steps per second')
    ap.add_argument('--token', default=secrets.token_hex(16), help='default: a new random one')
    args = ap.parse_args()
    TOKEN = args.token
    SIM = Sim(args.steps, args.rate)
    server = ThreadingHTTPServer(('127.0.0.1', args.port), Handler)
    server.daemon_threads = True
    threading.Thread(target=SIM.run, daemon=True).start()
    print(f'http://127.0.0.1:{server.server_port}/?token={TOKEN}', flush=True)
    server.serve_forever()
