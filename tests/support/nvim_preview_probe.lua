-- Run by tests/test_lsp_preview.py in a headless Neovim 0.7+ with editors/neovim/urdf_lint.lua:
-- once the first diagnostics arrived, :UrdfLintPreview's request (M.preview), then every 100 ms
-- write {url, cursor = {line, col}, file} to URDF_LINT_NVIM_OUT (the test clicks in the page,
-- the cursor must move). When the file OUT.move appears (a 1-based line), the cursor goes
-- there and CursorHold fires (the page's highlight must follow); OUT.quit ends it.
local out = os.getenv("URDF_LINT_NVIM_OUT")
local bufnr = vim.api.nvim_get_current_buf()
local state = { url = "", moved = false }
local asked = false
local plugin
vim.g.urdf_lint_cmd = { os.getenv("URDF_LINT_PY"), "-m", "urdf_lint", "server" }
vim.g.urdf_lint_open_preview = false
vim.g.urdf_lint_handlers = {
  ["textDocument/publishDiagnostics"] = function(err, result, ctx, config)
    vim.lsp.diagnostic.on_publish_diagnostics(err, result, ctx, config)
    if not asked then
      asked = true
      plugin.preview(bufnr, function(r) state.url = r.url end)
    end
  end,
}
plugin = dofile(os.getenv("URDF_LINT_NVIM_PLUGIN"))
plugin.start(bufnr)
local function exists(p)
  local f = io.open(p, "r")
  if f then
    local s = f:read("*a")
    f:close()
    return s
  end
  return nil
end
local timer = vim.loop.new_timer()
timer:start(100, 100, vim.schedule_wrap(function()
  local move = exists(out .. ".move")
  if move and not state.moved then
    vim.api.nvim_win_set_cursor(0, { tonumber(move), 4 })
    vim.cmd("doautocmd CursorHold")
    state.moved = true
  end
  local p = vim.api.nvim_win_get_cursor(0)
  state.cursor = { p[1], p[2] }
  state.file = vim.api.nvim_buf_get_name(0)
  local f = io.open(out .. ".tmp", "w")
  f:write(vim.fn.json_encode(state))
  f:close()
  os.rename(out .. ".tmp", out)
  if exists(out .. ".quit") then
    vim.cmd("qall!")
  end
end))
vim.defer_fn(function() vim.cmd("qall!") end, 120000)
