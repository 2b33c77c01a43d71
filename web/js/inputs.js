// Every input the page sends to a live run, by kind, and the REST request it
// becomes. Session.input(kind, payload) is the one place that sends them, in
// the manner of three.js editor's editor.execute(command): the modules say
// what the user did, not which URL takes it.
const enc = encodeURIComponent;

export const INPUT_KINDS = {
  control: (p) => ['POST', 'control', p],             // {action: play|pause|step|reset|stop|take|release}
  joystick: (p) => ['POST', 'joystick', p],           // {linear, angular}
  params: (p) => ['PATCH', 'params', p],              // {name: value, ...}
  method: (p) => ['POST', 'method', p],               // {name, params?}
  obstacle_add: (p) => ['POST', 'obstacles', p],      // an obstacle as in the scenario format
  obstacle_move: (p) => ['PUT', `obstacles/${enc(p.id)}`, { position: p.position }],
  obstacle_delete: (p) => ['DELETE', `obstacles/${enc(p.id)}`, undefined],
};

// {verb, path, body} of an input to run `runId`; throws on an unknown kind
// or a run id that is not a positive integer.
export function inputRequest(kind, runId, payload) {
  const route = Object.hasOwn(INPUT_KINDS, kind) ? INPUT_KINDS[kind] : null;
  if (!route) throw new Error(`unknown input kind "${kind}"`);
  if (!Number.isInteger(runId) || runId <= 0) throw new Error(`input "${kind}" needs a run id, not ${runId}`);
  const [verb, tail, body] = route(payload || {});
  return { verb, path: `/api/runs/${runId}/${tail}`, body };
}
