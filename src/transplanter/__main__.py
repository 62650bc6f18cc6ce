from transplanter.entry_point import console

console()
