// Minimal landing page until the dashboard lands: lists what the API serves.
async function list(url, element, text) {
  const response = await fetch(url);
  const items = await response.json();
  const ul = document.getElementById(element);
  for (const item of items) {
    const li = document.createElement('li');
    li.textContent = text(item);
    ul.appendChild(li);
  }
}
list('/api/methods', 'methods', (m) => `${m.name}: ${m.description}`);
list('/api/scenarios', 'scenarios', (s) => `${s.name}: ${s.description}`);
list('/api/runs?limit=20', 'runs', (r) => `#${r.id} ${r.scenario} / ${r.method} (${r.mode}, ${r.status}, ${r.frames} frames)`);
