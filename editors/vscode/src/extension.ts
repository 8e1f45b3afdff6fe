// The urdf-lint language client: starts `urdf-lint server` (LSP over stdio) for xacro,
// URDF, the YAML files xacro.load_yaml reads and pyproject.toml (its [tool.urdf-lint]).
import * as vscode from "vscode";
import {
  ExecuteCommandRequest,
  LanguageClient,
  LanguageClientOptions,
  ServerOptions,
  TransportKind,
} from "vscode-languageclient/node";

let client: LanguageClient | undefined;

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  const command = vscode.workspace
    .getConfiguration("urdf-lint")
    .get<string[]>("command", ["urdf-lint", "server"]);
  const serverOptions: ServerOptions = {
    command: command[0],
    args: command.slice(1),
    transport: TransportKind.stdio,
  };
  const clientOptions: LanguageClientOptions = {
    documentSelector: [
      { scheme: "file", pattern: "**/*.xacro" },
      { scheme: "file", pattern: "**/*.urdf" },
      { scheme: "file", pattern: "**/*.srdf" },
      { scheme: "file", language: "yaml" },
      { scheme: "file", pattern: "**/pyproject.toml" },
    ],
    synchronize: {
      fileEvents: vscode.workspace.createFileSystemWatcher("**/*.{xacro,urdf,srdf,yaml,toml}"),
    },
  };
  client = new LanguageClient("urdf-lint", "urdf-lint", serverOptions, clientOptions);
  context.subscriptions.push(client);
  await client.start();
  // the 3D preview of the current file (the server's `urdf-lint.preview` command serves it
  // from its own lint, unsaved edits included, and answers its URL, the link or joint under
  // the cursor highlighted); then the highlight follows the cursor in that file
  const previewed = new Set<string>();
  context.subscriptions.push(
    vscode.commands.registerCommand("urdf-lint.showPreview", async () => {
      const editor = vscode.window.activeTextEditor;
      if (!client || !editor) {
        return;
      }
      const pos = editor.selection.active;
      const result = (await client.sendRequest(ExecuteCommandRequest.type, {
        command: "urdf-lint.preview",
        arguments: [editor.document.uri.toString(), pos.line, pos.character],
      })) as { url: string; highlight: string } | null;
      if (result && result.url) {
        previewed.add(editor.document.uri.toString());
        await vscode.env.openExternal(vscode.Uri.parse(result.url, true));
      }
    }),
  );
  let pause: ReturnType<typeof setTimeout> | undefined;
  context.subscriptions.push(
    vscode.window.onDidChangeTextEditorSelection((event) => {
      const uri = event.textEditor.document.uri.toString();
      if (!client || !previewed.has(uri)) {
        return;
      }
      const pos = event.selections[0].active;
      if (pause) {
        clearTimeout(pause);
      }
      pause = setTimeout(() => {
        void client?.sendRequest(ExecuteCommandRequest.type, {
          command: "urdf-lint.previewHighlight",
          arguments: [uri, pos.line, pos.character],
        });
      }, 250);
    }),
  );
}

export async function deactivate(): Promise<void> {
  if (client) {
    await client.stop();
  }
}
