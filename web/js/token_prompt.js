// The token dialog: asked by api.js when the server answers 401, it resolves
// to what the user typed ('' on Cancel or Escape).
const $ = (id) => document.getElementById(id);

export function askForToken(refused) {
  const dialog = $('token-dialog');
  const input = $('token-input');
  $('token-why').textContent = refused
    ? 'The server refused that token. Type the token it was started with (--token or RRLAB_TOKEN).'
    : 'It was started with a token (--token or RRLAB_TOKEN). Type it once: this tab keeps it until you close it.';
  input.value = '';
  return new Promise((resolve) => {
    dialog.onclose = () => resolve(dialog.returnValue === 'ok' ? input.value : '');
    dialog.returnValue = '';
    dialog.showModal();
    input.focus();
  });
}
