// Where everything of an exported figure goes (exports.js figurePng): the
// views, each chart under its title, a legend whose entries wrap to further
// rows, and caption lines wrapped at word breaks to the figure's width. Pure
// (`measure(text, font)` gives a text's width), so that tests check the boxes:
// nothing wider than the figure, no text on other text.

// The lines of `text` no wider than `width` (breaking at spaces, then after
// ",;" and "_", then anywhere in a word longer than the line).
export function wrapText(text, width, measure) {
  const lines = [];
  let line = '';
  for (const word of String(text).split(/(?<=[ ,;_])/)) {
    if (measure(line + word) <= width) { line += word; continue; }
    if (line.trim()) lines.push(line.trimEnd());
    line = '';
    let rest = word;
    while (measure(rest) > width && rest.length > 1) {
      let n = rest.length - 1;
      while (n > 1 && measure(rest.slice(0, n)) > width) --n;
      lines.push(rest.slice(0, n));
      rest = rest.slice(n);
    }
    line = rest;
  }
  if (line.trim() || !lines.length) lines.push(line.trimEnd());
  return lines;
}

// { height, boxes: [{kind: 'views'|'chart-title'|'chart'|'swatch'|'legend'|'caption', text?, font?, colour?, x, y, w, h}] };
// a text box's y is its top, its baseline y + 0.8 h.
export function figureLayout({ width, viewHeight, chartHeight, charts, lanes, meta }, measure) {
  const line = Math.round(width * 0.016);
  const margin = Math.round(width * 0.01);
  const inner = width - 2 * margin;
  const boxes = [];
  let y = 0;
  boxes.push({ kind: 'views', x: 0, y, w: width, h: viewHeight });
  y += viewHeight;
  const titleFont = `600 ${Math.round(line * 0.9)}px system-ui, sans-serif`;
  for (const chart of charts) {
    y += line * 0.3;
    for (const text of wrapText(chart.title, inner, (t) => measure(t, titleFont))) {
      boxes.push({ kind: 'chart-title', text, font: titleFont, colour: '#37474f', x: margin, y, w: measure(text, titleFont), h: line });
      y += line * 1.2;
    }
    boxes.push({ kind: 'chart', chart, x: 0, y, w: width, h: chartHeight });
    y += chartHeight;
  }
  // the legend: a swatch and a label per lane, a new row when the next would not fit
  const legendFont = `600 ${line}px system-ui, sans-serif`;
  y += line * 0.6;
  let x = margin;
  for (const lane of lanes) {
    const swatch = line * 1.4;
    const room = inner - swatch;
    const texts = wrapText(lane.label, room, (t) => measure(t, legendFont));
    const w = swatch + Math.max(...texts.map((t) => measure(t, legendFont)));
    if (x > margin && x + w > margin + inner) { x = margin; y += line * 1.4; }
    boxes.push({ kind: 'swatch', colour: lane.colour, x, y: y + line * 0.2, w: line, h: line * 0.8 });
    texts.forEach((text, i) => boxes.push({ kind: 'legend', text, font: legendFont, colour: '#263238', x: x + swatch, y: y + i * line * 1.25, w: measure(text, legendFont), h: line }));
    y += (texts.length - 1) * line * 1.25;
    x += w + line * 2;
  }
  y += line * 1.6;
  const captionFont = `${Math.round(line * 0.85)}px system-ui, sans-serif`;
  for (const text of meta) {
    for (const part of wrapText(text, inner, (t) => measure(t, captionFont))) {
      boxes.push({ kind: 'caption', text: part, font: captionFont, colour: '#455a64', x: margin, y, w: measure(part, captionFont), h: line });
      y += line * 1.3;
    }
  }
  return { height: Math.ceil(y + line * 0.6), boxes };
}
