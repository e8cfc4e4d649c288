// End-to-end test of graftal serve's page, in a real (headless) Chromium.
//
//   node tests/e2e/page.mjs URL SCREENSHOT_OUT
//
// URL is a running `graftal serve FILE` (any pfg file: the test replaces the
// text first, so it depends on nothing but the server). playwright-core comes
// from web/node_modules (`npm ci` in web/); the browser is $GRAFTAL_CHROMIUM,
// by default /usr/bin/chromium. Every wait is bounded, so it never hangs.
// It prints one line per step passed and a closing "N passed, N failed".

import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const require = createRequire(path.join(here, "..", "..", "web", "package.json"));
const { chromium } = require("playwright-core");

const WAIT_MS = 10_000;
const WHOLE_RUN_MS = 120_000;

// The quadratic Koch island (ABOP Fig. 1.6), valid pfg with no warnings:
// the headers in the order the book's program reads them. Two steps, so
// that the production shows in the picture (with none, only the axiom is).
const KOCH = "derivation length: 2\nangle factor: 4\naxiom: F-F-F-F\nF --> F-F+F+FF-F-F+F\n";
// The production's line with a mistake (`->` for `-->`) and another
// successor, so that the corrected text draws a different picture.
const PRODUCTION_LINE = 4;
const BROKEN_LINE = "F -> F+F-F-F+F";
const FIXED_LINE = "F --> F+F-F-F+F";

class StepFailed extends Error {}

function check(condition, message) {
  if (!condition) throw new StepFailed(message);
}

const [url, screenshotOut] = process.argv.slice(2);
if (!url || !screenshotOut) {
  console.error("usage: node tests/e2e/page.mjs URL SCREENSHOT_OUT");
  process.exit(2);
}

// ---- helpers that talk to the page ----

/** Replaces the editor's whole text, as a user's edit would. */
async function setText(page, text) {
  await page.evaluate((t) => {
    const view = window.graftalEditor;
    view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: t } });
  }, text);
}

async function replaceLine(page, number, text) {
  await page.evaluate(
    ([n, t]) => {
      const view = window.graftalEditor;
      const line = view.state.doc.line(n);
      view.dispatch({ changes: { from: line.from, to: line.to, insert: t } });
    },
    [number, text],
  );
}

const seqOf = (page) => page.evaluate(() => Number(document.body.dataset.seq || 0));

/** Waits until an update newer than `after` is shown and no newer one is due. */
async function settled(page, after, what) {
  try {
    await page.waitForFunction(
      (a) => Number(document.body.dataset.seq || 0) > a && document.body.dataset.settled === "true",
      after,
      { timeout: WAIT_MS },
    );
  } catch {
    const status = await page.textContent("#status");
    throw new StepFailed(`no answer to ${what} within ${WAIT_MS / 1000} s (status: ${status})`);
  }
  return seqOf(page);
}

/** Waits for the growth frames of the update shown. */
async function framesLoaded(page) {
  try {
    await page.waitForFunction(
      () => document.body.dataset.framesSeq === document.body.dataset.seq && Number(document.body.dataset.frames) > 0,
      null,
      { timeout: WAIT_MS },
    );
  } catch {
    const note = await page.textContent("#growth-note");
    throw new StepFailed(`the frames did not arrive within ${WAIT_MS / 1000} s (${note || "no message"})`);
  }
  return page.evaluate(() => Number(document.body.dataset.frames));
}

const drawnCount = (page) => page.locator("#picture [data-src]").count();
const pictureHtml = (page) => page.innerHTML("#picture");

async function setSteps(page, steps) {
  const before = await seqOf(page);
  await page.fill("#steps", String(steps));
  await settled(page, before, `steps ${steps}`);
  return framesLoaded(page);
}

/** The middle of a drawn element's outline, in page coordinates. */
function pointOn(element) {
  const box = element.getBoundingClientRect();
  if (typeof element.getTotalLength !== "function") return { x: box.x + box.width / 2, y: box.y + box.height / 2 };
  const p = element.getPointAtLength(element.getTotalLength() / 2);
  const m = element.getScreenCTM();
  return { x: m.a * p.x + m.c * p.y + m.e, y: m.b * p.x + m.d * p.y + m.f };
}

// ---- the steps ----

const steps = [
  ["loads the page and draws the Koch island", async (page) => {
    await page.goto(url, { timeout: WAIT_MS });
    await page.waitForSelector("#editor .cm-editor", { timeout: WAIT_MS });
    await page.waitForFunction(() => window.graftalEditor && document.body.dataset.seq, null, { timeout: WAIT_MS });
    const before = await seqOf(page);
    await setText(page, KOCH);
    await settled(page, before, "the Koch island");
    await page.waitForSelector("#picture svg", { timeout: WAIT_MS });
    const errors = await page.locator("li.diag.error").count();
    check(errors === 0, `the Koch island has ${errors} error(s) listed`);
    check(!(await page.isVisible("#stale-badge")), "the stale badge shows for a valid text");
  }],

  [`a mistake on line ${PRODUCTION_LINE} is underlined, listed and makes the picture stale`, async (page) => {
    const before = await seqOf(page);
    await replaceLine(page, PRODUCTION_LINE, BROKEN_LINE);
    await settled(page, before, "the mistake");
    const underlinedLine = await page.evaluate(() => {
      const mark = document.querySelector("#editor .cm-lintRange-error");
      const line = mark?.closest(".cm-line");
      return line ? [...line.parentElement.children].indexOf(line) + 1 : 0;
    });
    check(underlinedLine === PRODUCTION_LINE,
      `expected an error underline on line ${PRODUCTION_LINE}, found ${underlinedLine || "none"}`);
    const listed = await page.locator(`li.diag[data-line="${PRODUCTION_LINE}"]`).count();
    check(listed > 0, `no li.diag with data-line="${PRODUCTION_LINE}" listed`);
    check(await page.isVisible("#stale-badge"), "#stale-badge is not visible while the text has errors");
  }],

  ["fixing it clears the list and redraws the picture", async (page) => {
    const stalePicture = await pictureHtml(page);
    const before = await seqOf(page);
    const fix = page.locator(`li.diag[data-line="${PRODUCTION_LINE}"] button.fix`).first();
    if ((await fix.count()) > 0) await fix.click({ timeout: WAIT_MS });
    else await replaceLine(page, PRODUCTION_LINE, FIXED_LINE);
    await settled(page, before, "the fix");
    const text = await page.evaluate((n) => window.graftalEditor.state.doc.line(n).text, PRODUCTION_LINE);
    check(text === FIXED_LINE,
      `after the fix line ${PRODUCTION_LINE} reads ${JSON.stringify(text)}, not ${JSON.stringify(FIXED_LINE)}`);
    const listed = await page.locator("#diagnostics li.diag").count();
    check(listed === 0, `${listed} diagnostic(s) still listed after the fix`);
    check(!(await page.isVisible("#stale-badge")), "#stale-badge still visible after the fix");
    check((await pictureHtml(page)) !== stalePicture, "the picture did not change after the fix");
  }],

  ["the growth slider shows fewer drawn elements at step 1 than at 3", async (page) => {
    let before = await seqOf(page);
    await setText(page, KOCH);
    await settled(page, before, "the Koch island again");
    const frames = await setSteps(page, 3);
    check(frames === 4, `expected 4 frames (steps 0..3), got ${frames}`);
    const atThree = await drawnCount(page);
    check(atThree > 0, "the picture has no drawn elements with data-src");
    await page.focus("#slider");
    await page.keyboard.press("Home");
    await page.keyboard.press("ArrowRight");
    const value = await page.inputValue("#slider");
    check(value === "1", `the slider is at ${value}, not 1`);
    const atOne = await drawnCount(page);
    check(atOne > 0 && atOne < atThree, `step 1 draws ${atOne} elements, step 3 ${atThree}`);
  }],

  ["hovering a drawn element marks the symbol that drew it", async (page) => {
    const target = page.locator("#picture [data-src]").nth(0);
    const point = await target.evaluate(pointOn);
    await page.mouse.move(point.x, point.y);
    await page.waitForSelector("#editor .cm-drew", { timeout: WAIT_MS });
    const found = await page.evaluate(() => {
      const hot = document.querySelector("#picture .hot");
      const [from, to] = (hot?.getAttribute("data-src") || "").split("-").map(Number);
      const marked = [...document.querySelectorAll("#editor .cm-drew")].map((e) => e.textContent).join("");
      return { hot: Boolean(hot), marked, source: hot ? window.graftalEditor.state.sliceDoc(from, to) : "" };
    });
    check(found.hot, "no picture element has the class hot under the mouse");
    check(found.marked !== "" && found.marked === found.source,
      `the cm-drew mark reads ${JSON.stringify(found.marked)}, the element's data-src ${JSON.stringify(found.source)}`);
    check(/^\S+$/.test(found.marked) && KOCH.includes(found.marked), `${JSON.stringify(found.marked)} is not a symbol of the text`);
    await page.mouse.move(0, 0);
  }],

  ["a screenshot of the picture at steps 2", async (page) => {
    const frames = await setSteps(page, 2);
    check(frames === 3, `expected 3 frames (steps 0..2), got ${frames}`);
    await page.locator("#picture").screenshot({ path: screenshotOut, timeout: WAIT_MS });
    console.log(`  (screenshot: ${screenshotOut})`);
  }],
];

async function main() {
  const browser = await chromium.launch({
    executablePath: process.env.GRAFTAL_CHROMIUM || "/usr/bin/chromium",
    args: ["--no-sandbox"],
    headless: true,
    timeout: WAIT_MS * 3,
  });
  let passed = 0;
  let failed = 0;
  try {
    const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
    page.setDefaultTimeout(WAIT_MS);
    const pageErrors = [];
    page.on("pageerror", (err) => pageErrors.push(err.message));
    for (const [name, run] of steps) {
      try {
        await run(page);
        check(pageErrors.length === 0, `the page threw: ${pageErrors.join("; ")}`);
        passed += 1;
        console.log(`ok ${passed} - ${name}`);
      } catch (err) {
        failed += 1;
        const why = err instanceof StepFailed ? err.message : err.stack || String(err);
        console.log(`not ok ${passed + failed} - ${name}\n  ${why}`);
        break; // later steps build on this one
      }
    }
  } finally {
    await browser.close();
  }
  const skipped = steps.length - passed - failed;
  console.log(`e2e: ${passed} passed, ${failed} failed${skipped ? `, ${skipped} skipped` : ""}`);
  return failed === 0 ? 0 : 1;
}

const guard = setTimeout(() => {
  console.log(`e2e: the whole run took over ${WHOLE_RUN_MS / 1000} s; giving up`);
  process.exit(1);
}, WHOLE_RUN_MS);
guard.unref();

main().then(
  (code) => process.exit(code),
  (err) => {
    console.log(`e2e: could not run: ${err.stack || err}`);
    process.exit(1);
  },
);
