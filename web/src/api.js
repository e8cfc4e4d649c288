// The server's JSON API (see src/serve in the Rust crate). Every failure
// comes back as a non-2xx status with `{"error": "..."}`; callers get an
// ApiError carrying that message, so the page can show it as it is.

export class ApiError extends Error {}

async function failure(response) {
  let message = `${response.status} ${response.statusText}`;
  try {
    const body = await response.json();
    if (body && typeof body.error === "string") message = body.error;
  } catch {
    // Not JSON (a proxy's page, say): the status line is all we have.
  }
  return new ApiError(message);
}

async function send(path, init) {
  let response;
  try {
    response = await fetch(path, init);
  } catch (err) {
    throw new ApiError(`the server does not answer (${err.message})`);
  }
  if (!response.ok) throw await failure(response);
  return response;
}

export async function getJson(path) {
  return (await send(path)).json();
}

function postInit(body) {
  return {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify(body),
  };
}

export async function postJson(path, body) {
  return (await send(path, postInit(body))).json();
}

/** POSTs and returns the raw answer: a blob and the filename the server gave. */
export async function postForFile(path, body, fallbackName) {
  const response = await send(path, postInit(body));
  const disposition = response.headers.get("Content-Disposition") || "";
  const named = /filename\*?=(?:UTF-8'')?"?([^";]+)"?/i.exec(disposition);
  const name = named ? decodeURIComponent(named[1]) : fallbackName;
  return { blob: await response.blob(), name };
}
