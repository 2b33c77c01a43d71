// web/js/state.js: the one command path. app.execute({type, ...}) runs the
// handler defined for the type and returns its result; a failure (the
// handler's, or an unknown type) rejects and is shown on the message line,
// unless the command says report: false; setSession is the one place the
// session on screen changes, and the panels hear of it.
import { test } from 'node:test';
import assert from 'node:assert/strict';

import { app } from '../../../web/js/state.js';

const messages = [];
app.signals.message.add((what, kind) => messages.push([kind, what instanceof Error ? what.message : what]));

test('a command runs its handler and resolves with its result', async () => {
  const seen = [];
  app.define({ double: (c) => { seen.push(c.type); return 2 * c.value; } });
  assert.equal(await app.execute({ type: 'double', value: 21 }), 42);
  assert.deepEqual(seen, ['double'], 'the handler runs once, at once');
});

test('a failure rejects and is reported, unless the command says not to', async () => {
  messages.length = 0;
  app.define({ fail: () => { throw new Error('refused'); }, failLater: async () => { throw new Error('refused later'); } });
  await assert.rejects(app.execute({ type: 'fail' }), /refused/);
  await assert.rejects(app.execute({ type: 'failLater' }), /refused later/);
  await assert.rejects(app.execute({ type: 'fail', report: false }), /refused/);
  await new Promise((r) => setImmediate(r));
  assert.deepEqual(messages, [['error', 'refused'], ['error', 'refused later']]);
});

test('an unknown command is refused, not run', async () => {
  messages.length = 0;
  for (const type of ['no_such_command', 'toString', '__proto__']) {
    await assert.rejects(app.execute({ type }), /unknown command/, type);
  }
  await new Promise((r) => setImmediate(r));
  assert.equal(messages.length, 3);
});

test('a failure nobody awaits is handled (no unhandled rejection)', async () => {
  let unhandled = 0;
  const count = () => { unhandled++; };
  process.on('unhandledRejection', count);
  app.define({ fail: () => { throw new Error('ignored by its caller'); } });
  app.execute({ type: 'fail' });
  await new Promise((r) => setTimeout(r, 0));
  process.off('unhandledRejection', count);
  assert.equal(unhandled, 0);
});

test('setSession closes the old session and tells the panels; a page gives way to it', () => {
  const heard = [];
  app.signals.sessionChanged.add((s) => heard.push(['session', s && s.name]));
  app.signals.pageChanged.add((p) => heard.push(['page', p && p.name]));
  const closed = [];
  const session = (name) => ({ name, lanes: [], close: () => closed.push(name) });
  app.setPage({ name: 'paper', key: 'qiu' });
  assert.equal(app.page.name, 'paper');
  const a = session('a');
  app.setSession(a);
  assert.equal(app.session, a);
  assert.equal(app.page, null);
  app.setPlayhead(7, null);
  app.setSession(session('b'));
  assert.deepEqual(closed, ['a']);
  assert.equal(app.playhead, null, 'a new session starts with no replay frame');
  assert.deepEqual(heard, [['session', null], ['page', 'paper'], ['page', null], ['session', 'a'], ['session', 'b']]);
});
