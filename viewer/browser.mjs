// browser.mjs — opens the viewer in headless Chromium, for the test and for
// tools/viewer_picture.mjs. It is Debian's Chromium (apt-get install
// chromium) driven by playwright-core: Playwright's own browser downloads are
// not reachable from the machines this project runs on.
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

export const chromiumPath = process.env.CHROMIUM ?? '/usr/bin/chromium';

// The background-networking flags keep Chromium from calling out (sync,
// updates, field trials): on a closed network those calls fail and slow it
// down. --disable-gpu leaves WebGL to SwiftShader, Chromium's software GL,
// which the last three flags ask for by name; newer Chromiums give software
// WebGL only with --enable-unsafe-swiftshader.
export const chromiumArgs = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--use-gl=angle',
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
];

/// A page of width × height CSS pixels (at one device pixel each) in a fresh
/// profile; close() ends the browser and removes the profile.
export async function openPage({ width = 960, height = 540, timeout = 30000 } = {}) {
  const profile = await mkdtemp(join(tmpdir(), 'impulse-viewer-chromium-'));
  let context;
  try {
    context = await chromium.launchPersistentContext(profile, {
      executablePath: chromiumPath,
      headless: true,
      args: chromiumArgs,
      viewport: { width, height },
      deviceScaleFactor: 1,
      timeout,
    });
  } catch (error) {
    await rm(profile, { recursive: true, force: true });
    throw error;
  }
  const page = context.pages()[0] ?? (await context.newPage());
  page.setDefaultTimeout(timeout);
  const close = async () => {
    await context.close();
    await rm(profile, { recursive: true, force: true });
  };
  return { page, close };
}

/// Opens `url` and waits until window.viewer has loaded its file (or
/// failed, which throws here with the viewer's message).
export async function openViewer(page, url, timeout = 30000) {
  await page.goto(url);
  await page.waitForFunction(() => window.viewer && (window.viewer.ready || window.viewer.error), null, { timeout });
  const error = await page.evaluate(() => window.viewer.error);
  if (error) throw new Error(`the viewer could not open ${url}: ${error}`);
}

/// The canvas as PNG bytes, straight from WebGL's drawing buffer: no page
/// controls on top, as a page screenshot would have.
export async function canvasPng(page) {
  const dataUrl = await page.evaluate(() => {
    window.viewer.renderNow();
    return window.viewer.canvas.toDataURL('image/png');
  });
  return Buffer.from(dataUrl.slice(dataUrl.indexOf(',') + 1), 'base64');
}
