// Just enough Markdown for the server's hover texts: paragraphs, `code`
// spans, **bold**, lists, `---` rules, # headings and code blocks, fenced
// or indented (graftal's explanations write their examples indented right
// under an "Example:" line, so an indented line always starts code here).
// Everything is escaped first, so the text can never inject markup.

const escapes = { "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" };

export function escapeHtml(text) {
  return text.replace(/[&<>"']/g, (c) => escapes[c]);
}

function inline(text) {
  // Code spans first, so that nothing inside them is read as emphasis.
  return text
    .split(/(`[^`]+`)/)
    .map((part, i) =>
      i % 2 === 1
        ? `<code>${escapeHtml(part.slice(1, -1))}</code>`
        : escapeHtml(part).replace(/\*\*(.+?)\*\*/g, "<strong>$1</strong>"),
    )
    .join("");
}

export function markdownToHtml(markdown) {
  const out = [];
  let paragraph = [];
  let list = null; // "ul" or "ol" while inside a list
  let fence = null; // the lines of an open fenced code block
  let indented = []; // the lines of an indented code block

  const closeParagraph = () => {
    if (paragraph.length) out.push(`<p>${inline(paragraph.join(" "))}</p>`);
    paragraph = [];
  };
  const closeList = () => {
    if (list) out.push(`</${list}>`);
    list = null;
  };
  const closeCode = () => {
    if (indented.length) out.push(`<pre><code>${escapeHtml(indented.join("\n"))}</code></pre>`);
    indented = [];
  };
  const closeBlocks = () => {
    closeParagraph();
    closeList();
    closeCode();
  };

  for (const line of markdown.split("\n")) {
    if (fence) {
      if (/^\s*```/.test(line)) {
        out.push(`<pre><code>${escapeHtml(fence.join("\n"))}</code></pre>`);
        fence = null;
      } else {
        fence.push(line);
      }
      continue;
    }
    if (/^(?: {4}|\t)/.test(line) && line.trim() !== "" && !list) {
      closeParagraph();
      indented.push(line.replace(/^(?: {4}|\t)/, ""));
      continue;
    }
    closeCode();
    const item = /^\s*(?:([-*+])|(\d+)[.)])\s+(.*)$/.exec(line);
    const heading = /^\s*#{1,6}\s+(.*)$/.exec(line);
    if (/^\s*```/.test(line)) {
      closeBlocks();
      fence = [];
    } else if (/^\s*(-{3,}|\*{3,}|_{3,})\s*$/.test(line)) {
      closeBlocks();
      out.push("<hr>");
    } else if (heading) {
      closeBlocks();
      out.push(`<p class="heading">${inline(heading[1])}</p>`);
    } else if (item) {
      closeParagraph();
      const kind = item[1] ? "ul" : "ol";
      if (list !== kind) {
        closeList();
        out.push(`<${kind}>`);
        list = kind;
      }
      out.push(`<li>${inline(item[3])}</li>`);
    } else if (line.trim() === "") {
      closeBlocks();
    } else {
      closeList();
      paragraph.push(line.trim());
    }
  }
  if (fence) out.push(`<pre><code>${escapeHtml(fence.join("\n"))}</code></pre>`);
  closeBlocks();
  return out.join("");
}
