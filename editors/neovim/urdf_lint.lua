-- urdf-lint language server for Neovim (0.7+): diagnostics, fixes, navigation and hover on
-- xacro, URDF, the YAML files they load and pyproject.toml. Put in your init.lua:
--   dofile("/path/to/urdf-lint/editors/neovim/urdf_lint.lua")
-- `urdf-lint` must be on PATH (or set vim.g.urdf_lint_cmd = {"/path/.venv/bin/urdf-lint", "server"}).
local function start(bufnr)
  local fname = vim.api.nvim_buf_get_name(bufnr)
  local root = vim.fs and vim.fs.dirname(vim.fs.find({ ".git", "package.xml", "pyproject.toml" },
    { upward = true, path = vim.fs.dirname(fname) })[1] or fname) or vim.fn.getcwd()
  local id = vim.lsp.start_client({
    name = "urdf-lint",
    cmd = vim.g.urdf_lint_cmd or { "urdf-lint", "server" },
    root_dir = root,
    handlers = vim.g.urdf_lint_handlers,
  })
  if id then
    vim.lsp.buf_attach_client(bufnr, id)
  end
end

vim.api.nvim_create_autocmd({ "BufReadPost", "BufNewFile" }, {
  pattern = { "*.xacro", "*.urdf", "*.urdf.xacro", "*.srdf", "*.yaml" },
  callback = function(args) start(args.buf) end,
})
return { start = start }
