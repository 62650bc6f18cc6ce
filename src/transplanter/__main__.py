from transplanter.cli import console

console()
